#include "bodyrec/detection/motion_regions.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {

void MotionRegionOptions::check() const {
  const auto fail = [](const char* field, const char* problem) { throw OptionError("MotionRegionOptions", field, problem); };
  if (!(work_width >= 32)) fail("work_width", "must be >= 32 pixels");
  if (history < 1) fail("history", "must be >= 1 frame");
  if (!(var_threshold > 0)) fail("var_threshold", "must be > 0");
  if (min_area < 0) fail("min_area", "must be >= 0");
  if (margin < 0) fail("margin", "must be >= 0");
  if (warmup_frames < 0) fail("warmup_frames", "must be >= 0 frames");
}

MotionRegions::MotionRegions(const MotionRegionOptions& options)
    : options_(options),
      model_(cv::createBackgroundSubtractorMOG2(options.history, options.var_threshold, false)) {
  options_.check();
}

std::vector<cv::Rect> merge_overlapping(std::vector<cv::Rect> rects) {
  bool merged = true;
  while (merged) {
    merged = false;
    for (size_t i = 0; i < rects.size() && !merged; ++i)
      for (size_t j = i + 1; j < rects.size() && !merged; ++j)
        if ((rects[i] & rects[j]).area() > 0) {
          rects[i] |= rects[j];
          rects.erase(rects.begin() + static_cast<std::ptrdiff_t>(j));
          merged = true;
        }
  }
  return rects;
}

std::vector<cv::Rect> MotionRegions::update(const cv::Mat& frame) {
  const double f = std::min(1.0, options_.work_width / frame.cols);
  cv::resize(frame, small_, cv::Size(), f, f, cv::INTER_AREA);
  model_->apply(small_, foreground_);
  const cv::Rect whole(0, 0, frame.cols, frame.rows);
  if (frames_++ < options_.warmup_frames) return {whole};

  cv::Mat mask;
  cv::morphologyEx(foreground_, mask, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}));
  cv::dilate(mask, mask, cv::getStructuringElement(cv::MORPH_RECT, {5, 9}));
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  std::vector<cv::Rect> regions;
  for (int i = 1; i < n; ++i) {
    if (stats.at<int>(i, cv::CC_STAT_AREA) / (f * f) < options_.min_area) continue;
    const cv::Rect r(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                     stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
    const double x = r.x / f, y = r.y / f, w = r.width / f, h = r.height / f;
    const double m = options_.margin * std::max(h, w);
    regions.push_back(cv::Rect(cv::Point(int(x - m), int(y - m)), cv::Point(int(x + w + m), int(y + h + m))) & whole);
  }
  return merge_overlapping(std::move(regions));
}

}  // namespace bodyrec
