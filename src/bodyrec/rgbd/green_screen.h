// Background removal ("green screen", thesis digest Ch5): every depth pixel that belongs to a body
// (body index 0..5) is mapped into the colour image with the intrinsics and extrinsics, and the colour
// at the rounded position is copied into a depth-sized BGRA image of that body; every other pixel is
// transparent (alpha 0). Pixels whose mapped position falls outside the colour image stay transparent.
// As in the thesis, there is no occlusion test between the two viewpoints, so a few pixels at body
// edges can take background colour (parallax of the 5 cm baseline).
#pragma once

#include <array>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/rgbd/recording.h"

namespace bodyrec {

class BackgroundRemoval {
 public:
  // Precomputes the per-pixel rays of the depth camera. REQUIRES: valid intrinsics in `meta`.
  explicit BackgroundRemoval(const RecordingMeta& meta);

  // One BGRA image (depth size) per body slot that has pixels in `body_index`: cutouts[slot] is empty
  // for absent slots. REQUIRES: depth CV_16U and body_index CV_8U of the depth size, color CV_8UC3 of
  // the colour size (throws InputError naming what disagrees otherwise).
  void apply(const cv::Mat& depth, const cv::Mat& body_index, const cv::Mat& color,
             std::array<cv::Mat, kMaxBodies>& cutouts) const;

 private:
  RecordingMeta meta_;
  std::vector<float> ray_x_, ray_y_;  // (u - cx) / fx and (cy - v) / fy of the depth camera
};

}  // namespace bodyrec
