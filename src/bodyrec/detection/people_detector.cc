#include "bodyrec/detection/people_detector.h"

#include <cmath>

namespace bodyrec {

std::vector<Detection> finalize_detections(std::vector<Detection> detections) {
  auto round_to = [](double v, double step) { return std::round(v / step) * step; };
  for (Detection& d : detections) {
    d.box = Box(round_to(d.box.x, 0.01), round_to(d.box.y, 0.01), round_to(d.box.width, 0.01),
                round_to(d.box.height, 0.01));
    d.score = round_to(d.score, 1e-6);
  }
  return detections;
}

}  // namespace bodyrec
