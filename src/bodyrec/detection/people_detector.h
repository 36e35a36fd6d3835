// The people-detector interface every detector implements, so the pipeline can swap them by name.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/core/geometry.h"

namespace bodyrec {

class PeopleDetector {
 public:
  virtual ~PeopleDetector() = default;
  // Detects people in one BGR frame. Detectors that use motion keep state: call on consecutive frames
  // of one source. ENSURES: boxes are tight to the body, in frame pixels, clipped to the frame, with
  // non-maximum suppression applied; higher score = more confident.
  virtual std::vector<Detection> detect(const cv::Mat& frame) = 0;
  // Detects people only near `expected` body boxes (where tracks say people are), for the frames between
  // full detections: much cheaper, and it finds nobody new. Same guarantees as detect(). Detectors with
  // no cheaper local search run a full detect().
  virtual std::vector<Detection> detect_near(const cv::Mat& frame, const std::vector<Box>& expected) {
    (void)expected;
    return detect(frame);
  }
  virtual std::string describe() const = 0;
};

}  // namespace bodyrec

namespace bodyrec {

// Rounds boxes and scores to the precision every sink writes (round_box_for_output).
std::vector<Detection> finalize_detections(std::vector<Detection> detections);

}  // namespace bodyrec
