// Regions of a frame where something moves, from a background model (OpenCV MOG2) on a downscaled copy.
// Used to restrict detection to where people can be; cheap compared with HOG on the whole frame.
#pragma once

#include <vector>

#include <opencv2/core/mat.hpp>
#include <opencv2/video/background_segm.hpp>

namespace bodyrec {

struct MotionRegionOptions {
  double work_width = 320;      // the background model runs on a copy this wide (pixels)
  int history = 200;            // MOG2 history (frames)
  double var_threshold = 16;    // MOG2 variance threshold
  double min_area = 30;         // in original pixels^2... scaled: components smaller than this are noise
  double margin = 0.5;          // each region grows by this fraction of its height on every side
  int warmup_frames = 0;        // frames before which the whole frame is returned (model still learning)
  void check() const;
};

class MotionRegions {
 public:
  explicit MotionRegions(const MotionRegionOptions& options);
  // Feeds one frame; returns non-overlapping rectangles (frame pixels) covering the moving parts, merged
  // when they overlap after the margin is added. Returns the whole frame during warm-up.
  std::vector<cv::Rect> update(const cv::Mat& frame);
  const cv::Mat& foreground() const { return foreground_; }  // last mask, at work size

 private:
  MotionRegionOptions options_;
  cv::Ptr<cv::BackgroundSubtractorMOG2> model_;
  cv::Mat small_, foreground_;
  int frames_ = 0;
};

// Merges rectangles that overlap until none do (the union box of each overlapping set).
std::vector<cv::Rect> merge_overlapping(std::vector<cv::Rect> rects);

}  // namespace bodyrec
