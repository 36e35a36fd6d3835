// Evaluation of colour-only runs on recordings with truth (bodyrec synth): which true person each tracked
// box shows. The recording's body index (which the colour pipeline never sees) is mapped into the colour
// image person by person (PartialScanExtractor::color_mask), and a box shows the person with the most
// visible pixels inside it, when those fill at least min_share of the box.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/rgbd/recording.h"

namespace bodyrec {

struct BoxTruth {
  std::vector<int> person;  // per box: index into frame.truth->people, -1 when none
  int visible = 0;          // people of the truth whose colour mask has at least min_visible_px pixels
};

// REQUIRES frame with truth, depth and body index (else every box gets -1 and visible is 0).
BoxTruth truth_for_boxes(const RecordingMeta& meta, const RgbdFrame& frame, const std::vector<cv::Rect>& boxes,
                         double min_share = 0.2, int min_visible_px = 1500);

}  // namespace bodyrec
