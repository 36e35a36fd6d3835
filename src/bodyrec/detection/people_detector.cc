#include "bodyrec/detection/people_detector.h"

#include <cmath>

namespace bodyrec {

std::vector<Detection> finalize_detections(std::vector<Detection> detections) {
  // Dividing by an exact power of ten gives the double nearest the decimal, which is what a parser
  // of the written text gets back, and what prints shortest in JSON.
  auto round_to = [](double v, double per_unit) { return std::round(v * per_unit) / per_unit; };
  for (Detection& d : detections) {
    d.box = Box(round_to(d.box.x, 100), round_to(d.box.y, 100), round_to(d.box.width, 100),
                round_to(d.box.height, 100));
    d.score = round_to(d.score, 1e6);
  }
  return detections;
}

}  // namespace bodyrec
