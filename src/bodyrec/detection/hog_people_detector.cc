#include "bodyrec/detection/hog_people_detector.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// Puts windows and their weights in one canonical order (position, size, weight).
void sort_windows(std::vector<cv::Rect>& rects, std::vector<double>& weights) {
  std::vector<size_t> order(rects.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    const cv::Rect &ra = rects[a], &rb = rects[b];
    return std::tie(ra.y, ra.x, ra.height, ra.width, weights[a]) <
           std::tie(rb.y, rb.x, rb.height, rb.width, weights[b]);
  });
  std::vector<cv::Rect> sorted_rects;
  std::vector<double> sorted_weights;
  for (size_t i : order) {
    sorted_rects.push_back(rects[i]);
    sorted_weights.push_back(weights[i]);
  }
  rects.swap(sorted_rects);
  weights.swap(sorted_weights);
}

// The windows and SVM scores of detectMultiScale before its grouping, computed as it does (the same
// pyramid, resizing and window placement) but collected level by level in level order. OpenCV's own
// (4.6 and later) appends each level's windows and its scores under two separate locks, so a level
// finishing on another thread between the two can pair scores with the wrong windows; under load,
// two identical runs then gave one detection different scores.
void pyramid_windows(const cv::HOGDescriptor& hog, const cv::Mat& image, double hit_threshold, cv::Size stride,
                     cv::Size padding, double step, std::vector<cv::Rect>& found, std::vector<double>& weights) {
  std::vector<double> scales;
  for (double scale = 1.0; static_cast<int>(scales.size()) < hog.nlevels; scale *= step) {
    scales.push_back(scale);
    if (cvRound(image.cols / scale) < hog.winSize.width || cvRound(image.rows / scale) < hog.winSize.height ||
        step <= 1) {
      if (scales.size() > 1) scales.pop_back();  // as OpenCV: the level where the window no longer fits goes
      break;
    }
  }
  std::vector<std::vector<cv::Rect>> level_rects(scales.size());
  std::vector<std::vector<double>> level_weights(scales.size());
  cv::parallel_for_(cv::Range(0, static_cast<int>(scales.size())), [&](const cv::Range& range) {
    std::vector<cv::Point> hits;
    for (int i = range.start; i < range.end; ++i) {
      const double scale = scales[static_cast<size_t>(i)];
      const cv::Size size(cvRound(image.cols / scale), cvRound(image.rows / scale));
      cv::Mat level = image;
      if (size != image.size()) cv::resize(image, level, size, 0, 0, cv::INTER_LINEAR_EXACT);
      hog.detect(level, hits, level_weights[static_cast<size_t>(i)], hit_threshold, stride, padding);
      const cv::Size window(cvRound(hog.winSize.width * scale), cvRound(hog.winSize.height * scale));
      for (const cv::Point& p : hits)
        level_rects[static_cast<size_t>(i)].emplace_back(cvRound(p.x * scale), cvRound(p.y * scale), window.width,
                                                          window.height);
    }
  });
  // As detectMultiScale returns them: clipped to the image, the ones left empty dropped.
  const cv::Rect inside(0, 0, image.cols, image.rows);
  found.clear();
  weights.clear();
  for (size_t i = 0; i < scales.size(); ++i)
    for (size_t j = 0; j < level_rects[i].size(); ++j) {
      const cv::Rect r = level_rects[i][j] & inside;
      if (r.area() <= 0) continue;
      found.push_back(r);
      weights.push_back(level_weights[i][j]);
    }
}

}  // namespace

void HogOptions::set_height_range(double min_height, double max_height) {
  const double window_height = (model == HogModel::kDaimler ? 96.0 : 128.0) * body_height;
  resize = window_height / min_height;
  levels = static_cast<int>(std::ceil(std::log(max_height / min_height) / std::log(scale))) + 1;
  this->min_height = min_height;
  this->max_height = max_height;
}

void HogOptions::check() const {
  if (win_stride < 1) throw UsageError("--win-stride must be >= 1");
  if (padding < 0) throw UsageError("--padding must be >= 0");
  if (!(scale > 1.0)) throw UsageError("--scale must be > 1");
  if (group_threshold < 0) throw UsageError("--group-threshold must be >= 0");
  if (!(resize > 0.05 && resize <= 8)) throw UsageError("--resize must be in (0.05, 8]");
  if (levels < 1) throw UsageError("--levels must be >= 1");
  if (!(nms_iou > 0 && nms_iou <= 1)) throw UsageError("--nms-iou must be in (0, 1]");
  if (roi.width < 0 || roi.height < 0) throw UsageError("--roi must have a positive size");
  if (adapt_after < 0) throw UsageError("--adapt-after must be >= 0");
  if (!(adapt_margin >= 0 && adapt_margin < 1)) throw UsageError("--adapt-margin must be in [0, 1)");
  if (!(local_region_margin >= 0 && local_region_margin <= 2)) throw UsageError("--local-region-margin must be in [0, 2]");
  if (!(local_height_margin >= 0 && local_height_margin < 0.5)) throw UsageError("--local-height-margin must be in [0, 0.5)");
  motion.check();
}

const char* to_string(HogModel model) { return model == HogModel::kDaimler ? "daimler" : "default"; }

std::optional<HogModel> parse_hog_model(const std::string& text) {
  if (text == "default") return HogModel::kDefault;
  if (text == "daimler") return HogModel::kDaimler;
  return std::nullopt;
}

const char* to_string(HogPreset preset) {
  switch (preset) {
    case HogPreset::kDefault: return "default";
    case HogPreset::kThesis: return "thesis";
    case HogPreset::kOpenCv: return "opencv";
  }
  return "?";
}

std::optional<HogPreset> parse_hog_preset(const std::string& text) {
  for (HogPreset p : {HogPreset::kDefault, HogPreset::kThesis, HogPreset::kOpenCv})
    if (text == to_string(p)) return p;
  return std::nullopt;
}

HogOptions hog_preset(HogPreset preset) {
  HogOptions o;
  switch (preset) {
    case HogPreset::kThesis:
      return o;  // the struct defaults are the thesis's call
    case HogPreset::kDefault:
      o.win_stride = 8;  // a multiple of the 8-pixel cell: OpenCV's fast path (stride 12 is slower)
      o.group_threshold = 1;  // measured on vtest.avi: AP50 0.809 vs 0.797 with 2, same cost
      o.scale = 1.08;
      o.set_height_range(60, 140);
      o.motion_roi = true;
      o.motion.warmup_frames = 1;  // the first frame has no motion yet: search all of it
      o.adapt_after = 40;
      return o;
    case HogPreset::kOpenCv:
      // OpenCV's people detection sample (samples/cpp/peopledetect.cpp): detectMultiScale(img, found, 0,
      // Size(8,8), Size(), 1.05, 2) on the whole image, each window then shrunk as the sample does (x + 10 %,
      // y + 7 %, 80 % of the width and height).
      o.hit_threshold = 0;
      o.win_stride = 8;
      o.padding = 0;
      o.body_width = 0.8;
      o.body_height = 0.8;
      o.body_center_x = 0.5;
      o.body_center_y = 0.47;
      return o;
  }
  return o;
}

HogPeopleDetector::HogPeopleDetector(const HogOptions& options) : options_(options) {
  options_.check();
  hog_for(options_.levels);
  if (options_.motion_roi) motion_.emplace(options_.motion);
  if (options_.motion_roi && options_.adapt_after > 0 && options_.min_height > 0)
    heights_.emplace(options_.adapt_after);
}

const cv::HOGDescriptor& HogPeopleDetector::hog_for(int levels) const {
  auto it = hogs_.find(levels);
  if (it != hogs_.end()) return it->second;
  cv::HOGDescriptor hog;
  if (options_.model == HogModel::kDaimler) {
    hog = cv::HOGDescriptor(cv::Size(48, 96), cv::Size(16, 16), cv::Size(8, 8), cv::Size(8, 8), 9);
    hog.setSVMDetector(cv::HOGDescriptor::getDaimlerPeopleDetector());
  } else {
    hog.setSVMDetector(cv::HOGDescriptor::getDefaultPeopleDetector());
  }
  hog.nlevels = levels;
  return hogs_.emplace(levels, hog).first->second;
}

HogPeopleDetector::Search HogPeopleDetector::plan(const cv::Rect& region) const {
  const Search configured{options_.resize, options_.levels, options_.padding};
  if (!heights_) return configured;
  const auto range = heights_->height_range(region.y, region.y + region.height, options_.adapt_margin);
  if (!range) return configured;
  const double lo = std::max(range->first, options_.min_height), hi = std::min(range->second, options_.max_height);
  if (!(hi > lo)) return configured;  // the fit says nobody fits here; stay safe
  const double window_height = hog_for(options_.levels).winSize.height * options_.body_height;
  return {window_height / lo,
          static_cast<int>(std::ceil(std::log(hi / lo) / std::log(options_.scale))) + 1, options_.padding};
}

Box HogPeopleDetector::body_box(const Box& w) const {
  const double cx = w.x + options_.body_center_x * w.width, cy = w.y + options_.body_center_y * w.height;
  const double bw = options_.body_width * w.width, bh = options_.body_height * w.height;
  return Box(cx - bw / 2, cy - bh / 2, bw, bh);
}

std::vector<Detection> HogPeopleDetector::detect_windows(const cv::Mat& frame, const cv::Rect& region) {
  return search(frame, region, {options_.resize, options_.levels, options_.padding});
}

std::vector<Detection> HogPeopleDetector::search(const cv::Mat& frame, const cv::Rect& region,
                                                 const Search& how) const {
  const cv::HOGDescriptor& hog = hog_for(how.levels);
  const double r = how.resize;
  cv::Mat image;
  cv::resize(frame(region), image, cv::Size(), r, r, r > 1 ? cv::INTER_LINEAR : cv::INTER_AREA);
  // detectMultiScale needs at least one window; pad small regions with border pixels.
  const cv::Size win = hog.winSize;
  const int pad_x = std::max(0, win.width - image.cols), pad_y = std::max(0, win.height - image.rows);
  if (pad_x || pad_y) cv::copyMakeBorder(image, image, 0, pad_y, 0, pad_x, cv::BORDER_REPLICATE);
  std::vector<cv::Rect> found;
  std::vector<double> weights;
  // Raw windows first, then grouped. pyramid_windows already returns them in a fixed order; the sort keeps
  // the canonical order every published figure was measured with (grouping averages boxes in input order).
  pyramid_windows(hog, image, options_.hit_threshold, cv::Size(options_.win_stride, options_.win_stride),
                  cv::Size(how.padding, how.padding), options_.scale, found, weights);
  sort_windows(found, weights);
  if (options_.group_threshold > 0) hog.groupRectangles(found, weights, options_.group_threshold, 0.2);
  std::vector<Detection> out;
  for (size_t i = 0; i < found.size(); ++i) {
    const Box b = scale_box(Box(found[i]), 1.0 / r);
    out.push_back({Box(b.x + region.x, b.y + region.y, b.width, b.height), weights[i]});
  }
  return out;
}

std::vector<Detection> HogPeopleDetector::search_regions(
    const cv::Mat& frame, const std::vector<std::pair<cv::Rect, Search>>& plan) const {
  // Regions are searched one after the other: HOG already spreads each search over the cores (by pyramid
  // level); searching regions in parallel instead was slower (measured: 47 vs 32 ms per frame for full
  // detections, no gain for searches near tracks).
  std::vector<Detection> detections;
  for (const auto& [region, how] : plan)
    for (Detection& d : search(frame, region, how)) {
      d.box = clip_box(body_box(d.box), frame.size());
      if (d.box.area() > 0) detections.push_back(d);
    }
  return finalize_detections(non_max_suppression(std::move(detections), options_.nms_iou));
}

std::vector<Detection> HogPeopleDetector::detect(const cv::Mat& frame) {
  const cv::Rect whole(0, 0, frame.cols, frame.rows);
  const cv::Rect base = options_.roi.area() > 0 ? (options_.roi & whole) : whole;
  std::vector<cv::Rect> regions{base};
  if (motion_) {
    regions.clear();
    for (const cv::Rect& m : motion_->update(frame)) {
      const cv::Rect r = m & base;
      if (r.area() > 0) regions.push_back(r);
    }
  }
  std::vector<std::pair<cv::Rect, Search>> plan_all;
  for (const cv::Rect& region : regions) plan_all.emplace_back(region, plan(region));
  auto result = search_regions(frame, plan_all);
  if (heights_)
    for (const Detection& d : result)
      if (d.score >= options_.adapt_min_score) heights_->add(d.box.y + d.box.height, d.box.height);
  return result;
}

std::vector<Detection> HogPeopleDetector::detect_near(const cv::Mat& frame, const std::vector<Box>& expected) {
  const cv::Rect whole(0, 0, frame.cols, frame.rows);
  const double window_body_height = hog_for(options_.levels).winSize.height * options_.body_height;
  const double lo = 1 - options_.local_height_margin, hi = 1 + options_.local_height_margin;
  const int levels = static_cast<int>(std::ceil(std::log(hi / lo) / std::log(options_.scale))) + 1;
  std::vector<std::pair<cv::Rect, Search>> plan_near;
  for (const Box& b : expected) {
    if (!(b.height > 1 && b.width > 1)) continue;
    // The detector window around the body box, grown by the margin (the person may have moved).
    const double ww = b.width / options_.body_width, wh = b.height / options_.body_height;
    const double cx = b.x + b.width / 2, cy = b.y + b.height / 2;
    const double wx = cx - options_.body_center_x * ww, wy = cy - options_.body_center_y * wh;
    const double m = options_.local_region_margin;
    const cv::Rect region = cv::Rect(cv::Point(static_cast<int>(std::floor(wx - m * ww)), static_cast<int>(std::floor(wy - m * wh))),
                                     cv::Point(static_cast<int>(std::ceil(wx + (1 + m) * ww)), static_cast<int>(std::ceil(wy + (1 + m) * wh)))) & whole;
    if (region.area() <= 0) continue;
    // No padding: the region already reaches past the expected window on every side.
    plan_near.emplace_back(region, Search{window_body_height / (lo * b.height), levels, 0});
  }
  return search_regions(frame, plan_near);
}

std::string HogPeopleDetector::describe() const {
  std::ostringstream s;
  s << "OpenCV HOG (" << to_string(options_.model) << " SVM, hit " << options_.hit_threshold << ", stride "
    << options_.win_stride << ", padding " << options_.padding << ", scale " << options_.scale << ", group "
    << options_.group_threshold << ", resize " << options_.resize << ", levels " << options_.levels
    << (options_.motion_roi ? ", motion regions" : "") << (heights_ ? ", scene-adaptive scales" : "") << ")";
  return s.str();
}

}  // namespace bodyrec
