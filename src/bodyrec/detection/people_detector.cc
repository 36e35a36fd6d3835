#include "bodyrec/detection/people_detector.h"

namespace bodyrec {

std::vector<Detection> finalize_detections(std::vector<Detection> detections) {
  for (Detection& d : detections) {
    d.box = round_box_for_output(d.box);
    d.score = round_score_for_output(d.score);
  }
  return detections;
}

}  // namespace bodyrec
