#include "bodyrec/detection/foreground_detector.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {

void ForegroundOptions::check() const {
  if (!(work_width >= 32)) throw OptionError("ForegroundOptions", "work_width", "must be >= 32 pixels");
  if (history < 1) throw OptionError("ForegroundOptions", "history", "must be >= 1 frame");
  if (!(var_threshold > 0)) throw OptionError("ForegroundOptions", "var_threshold", "must be > 0");
  if (warmup_frames < 0) throw OptionError("ForegroundOptions", "warmup_frames", "must be >= 0 frames");
  if (!(min_height > 0 && min_height < 1)) throw OptionError("ForegroundOptions", "min_height", "must be in (0, 1)");
  if (!(min_fill >= 0 && min_fill < 1)) throw OptionError("ForegroundOptions", "min_fill", "must be in [0, 1)");
  if (!(person_aspect > 0) || !(max_aspect >= person_aspect))
    throw OptionError("ForegroundOptions", "person_aspect", "must be > 0 and at most max_aspect");
}

ForegroundModel::ForegroundModel(const ForegroundOptions& options)
    : options_(options), model_(cv::createBackgroundSubtractorMOG2(options.history, options.var_threshold, true)) {
  options_.check();
}

void ForegroundModel::update(const cv::Mat& frame) {
  if (frame.empty()) throw InputError("foreground: empty frame");
  if (frames_ > 0 && frame.size() != frame_size_)
    throw InputError("foreground: frame size changed from " + std::to_string(frame_size_.width) + "x" +
                     std::to_string(frame_size_.height) + " to " + std::to_string(frame.cols) + "x" +
                     std::to_string(frame.rows));
  frame_size_ = frame.size();
  scale_ = std::min(1.0, options_.work_width / frame.cols);
  if (scale_ < 1) cv::resize(frame, small_, cv::Size(), scale_, scale_, cv::INTER_AREA);
  else small_ = frame;
  model_->apply(small_, raw_);
  ++frames_;
  // Shadows (127) are not foreground; specks go, and a body's parts (head, torso, legs of one colour with
  // the background between them) join along the vertical.
  cv::threshold(raw_, mask_, 200, 255, cv::THRESH_BINARY);
  const int k = std::max(1, static_cast<int>(std::lround(small_.cols / 160.0)));
  cv::morphologyEx(mask_, mask_, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_RECT, {k + 1, k + 1}));
  cv::morphologyEx(mask_, mask_, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_ELLIPSE, {2 * k + 1, 6 * k + 1}));
}

cv::Mat ForegroundModel::mask_in(const cv::Rect& box) const {
  if (mask_.empty()) return {};
  const cv::Rect b = box & cv::Rect({0, 0}, frame_size_);
  if (b.empty()) return {};
  const cv::Rect2d s(b.x * scale_, b.y * scale_, b.width * scale_, b.height * scale_);
  const cv::Rect small = cv::Rect(cv::Point(static_cast<int>(std::floor(s.x)), static_cast<int>(std::floor(s.y))),
                                  cv::Point(static_cast<int>(std::ceil(s.br().x)), static_cast<int>(std::ceil(s.br().y)))) &
                         cv::Rect(0, 0, mask_.cols, mask_.rows);
  if (small.empty()) return cv::Mat::zeros(b.size(), CV_8U);
  // Resample the covering work-size patch onto the box's pixels.
  cv::Mat patch;
  cv::resize(mask_(small), patch, cv::Size(), 1.0 / scale_, 1.0 / scale_, cv::INTER_LINEAR);
  const cv::Point offset(static_cast<int>(std::lround(small.x / scale_)), static_cast<int>(std::lround(small.y / scale_)));
  cv::Mat out = cv::Mat::zeros(b.size(), CV_8U);
  const cv::Rect in_patch = cv::Rect(b.tl() - offset, b.size()) & cv::Rect(0, 0, patch.cols, patch.rows);
  if (!in_patch.empty()) patch(in_patch).copyTo(out(cv::Rect(in_patch.tl() - (b.tl() - offset), in_patch.size())));
  cv::threshold(out, out, 127, 255, cv::THRESH_BINARY);
  return out;
}

namespace {

// The bounding box of the component's pixels in each column range [cuts[i], cuts[i + 1]) of `box`.
std::vector<cv::Rect> parts_between(const cv::Mat& component, const cv::Rect& box, const std::vector<int>& cuts) {
  std::vector<cv::Rect> out;
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    const cv::Rect strip(box.x + cuts[i], box.y, cuts[i + 1] - cuts[i], box.height);
    if (strip.width <= 0) continue;
    std::vector<cv::Point> points;
    cv::findNonZero(component(strip), points);
    if (points.empty()) continue;
    const cv::Rect r = cv::boundingRect(points);
    out.emplace_back(r.x + strip.x, r.y + strip.y, r.width, r.height);
  }
  return out;
}

// Foreground pixels per column of `box` over rows [y0, y1).
std::vector<int> column_counts(const cv::Mat& component, const cv::Rect& box, int y0, int y1) {
  std::vector<int> columns(static_cast<size_t>(box.width), 0);
  for (int y = y0; y < y1; ++y) {
    const uint8_t* row = component.ptr<uint8_t>(y);
    for (int x = box.x; x < box.br().x; ++x) columns[static_cast<size_t>(x - box.x)] += row[x] != 0;
  }
  return columns;
}

}  // namespace

std::vector<cv::Rect> split_component(const cv::Mat& component, const cv::Rect& box, const ForegroundOptions& o) {
  if (box.width > o.max_aspect * box.height) {
    // Wider than anyone: even parts, each cut at the thinnest column within a third of a part of its place.
    const int parts = std::max(2, static_cast<int>(std::lround(box.width / (o.person_aspect * box.height))));
    const std::vector<int> columns = column_counts(component, box, box.y, box.br().y);
    std::vector<int> cuts = {0};
    const double part = static_cast<double>(box.width) / parts;
    for (int i = 1; i < parts; ++i) {
      const int centre = static_cast<int>(std::lround(i * part)), reach = std::max(1, static_cast<int>(part / 3));
      int best = centre;
      for (int x = std::max(cuts.back() + 1, centre - reach); x <= std::min(box.width - 2, centre + reach); ++x)
        if (columns[static_cast<size_t>(x)] < columns[static_cast<size_t>(best)]) best = x;
      cuts.push_back(best);
    }
    cuts.push_back(box.width);
    return parts_between(component, box, cuts);
  }
  if (box.width <= o.person_aspect * box.height) return {box};
  // As wide as one or two people: two heads (runs of foreground at least a tenth of the height wide, apart,
  // in some band of rows in the top 30 %) are two people, cut in the middle of the gap between them.
  const int band = std::max(2, box.height / 20), min_run = std::max(2, box.height / 10);
  std::vector<std::pair<int, int>> runs;  // [begin, end) columns of the band with the most runs
  for (int y = box.y; y + band <= box.y + box.height * 3 / 10; y += std::max(1, band / 2)) {
    const std::vector<int> columns = column_counts(component, box, y, y + band);
    std::vector<std::pair<int, int>> here;
    for (int x = 0; x < box.width;) {
      if (columns[static_cast<size_t>(x)] == 0) {
        ++x;
        continue;
      }
      int end = x;
      while (end < box.width && columns[static_cast<size_t>(end)] > 0) ++end;
      if (end - x >= min_run) here.emplace_back(x, end);
      x = end;
    }
    if (here.size() > runs.size()) runs = here;
  }
  if (runs.size() < 2) return {box};
  std::vector<int> cuts = {0};
  for (size_t i = 0; i + 1 < runs.size(); ++i) cuts.push_back((runs[i].second + runs[i + 1].first) / 2);
  cuts.push_back(box.width);
  return parts_between(component, box, cuts);
}

ForegroundPeopleDetector::ForegroundPeopleDetector(const ForegroundOptions& options) : model_(options) {}

std::vector<Detection> ForegroundPeopleDetector::detect(const cv::Mat& frame) {
  model_.update(frame);
  const ForegroundOptions& o = model_.options();
  if (model_.frames() <= o.warmup_frames) return {};
  const cv::Mat& mask = model_.mask();
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  const double s = model_.scale(), min_h = o.min_height * mask.rows;
  std::vector<Detection> found;
  cv::Mat component;
  for (int i = 1; i < n; ++i) {
    const cv::Rect box(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                       stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
    if (box.height < min_h) continue;
    component = labels == i;
    for (const cv::Rect& r : split_component(component, box, o)) {
      if (r.height < min_h || r.height < r.width * 0.8) continue;  // people are taller than wide
      const double fill = cv::countNonZero(component(r)) / static_cast<double>(r.area());
      if (fill < o.min_fill) continue;
      found.push_back({Box(r.x / s, r.y / s, r.width / s, r.height / s), 0.5 + 0.5 * fill});
    }
  }
  for (Detection& d : found) d.box = clip_box(d.box, frame.size());
  return finalize_detections(non_max_suppression(std::move(found), 0.5, 0.8));
}

std::string ForegroundPeopleDetector::describe() const {
  const ForegroundOptions& o = model_.options();
  std::ostringstream s;
  s << "foreground (MOG2 history " << o.history << ", work width " << o.work_width << ")";
  return s.str();
}

}  // namespace bodyrec
