// The thesis's motion stage (digest Ch4, step 3): three-frame differential subtraction.
//
// With the last three grey frames prev, curr, next: d1 = |prev - next|, d2 = |next - curr|,
// motion = (d1 AND d2) > threshold. The AND keeps pixels that changed over both intervals, which removes
// the "ghost" a two-frame difference leaves where something was. If the standard deviation of the binary
// motion image is below max_deviation the motion is real (a huge spread means global change: lighting,
// camera shake) and the bounding rectangle of all motion pixels is the motion box.
//
// In a stream the newest frame is `next`, so the result describes the frame before it; bodyrec attributes
// it to the newest frame (one frame, 1/7 s on vtest.avi, of lag).
#pragma once

#include <optional>

#include <opencv2/core.hpp>

#include "bodyrec/core/geometry.h"

namespace bodyrec {

struct DifferentialMotionOptions {
  int threshold = 35;          // grey-level difference a pixel needs in both intervals (thesis: 35)
  double max_deviation = 20;   // motion is real when the motion image's std-dev is below this (thesis: 20)
  int erode = 2;               // erosion kernel size removing single-pixel noise (0 = none)
  double work_width = 384;     // frames are reduced to this width first (0 = full size); boxes are in frame pixels
  void check() const;          // throws UsageError naming the field
};

struct MotionResult {
  bool ready = false;            // false until three frames have been seen
  bool valid = false;            // ready, some motion, and the std-dev test passed
  double deviation = 0;          // std-dev of the binary motion image (0..255 scale, as in the thesis)
  int pixels = 0;                // motion pixels (at work size)
  std::optional<Box> box;        // bounding box of the motion pixels in frame pixels, when valid

  // Fraction (0..1) of the pixels of `box` (frame pixels) that moved. 0 before the stage is ready.
  double energy_in(const Box& box) const;

  cv::Mat mask;      // binary motion image at work size (CV_8U, 0/255)
  double scale = 1;  // work size / frame size
 private:
  friend class DifferentialMotion;
  cv::Mat integral_;  // of mask/255, for energy_in
};

class DifferentialMotion {
 public:
  explicit DifferentialMotion(const DifferentialMotionOptions& options = {});  // calls options.check()
  // Feeds the next frame (BGR or grey; all frames the same size) and returns the motion for it.
  const MotionResult& update(const cv::Mat& frame);
  const MotionResult& result() const { return result_; }

 private:
  DifferentialMotionOptions options_;
  cv::Mat prev_, curr_, next_;
  MotionResult result_;
};

}  // namespace bodyrec
