#include "bodyrec/reid/colour_truth.h"

#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "bodyrec/reid/partial_scan.h"

namespace bodyrec {

namespace {

// Each true person's body mask in the colour image, from the body index (what the RGB-D path's scans
// use): (index into the truth's people, mask); people without a body index or a visible mask are left out.
std::vector<std::pair<int, cv::Mat>> true_colour_masks(const RecordingMeta& meta, const RgbdFrame& frame) {
  std::vector<std::pair<int, cv::Mat>> out;
  if (!frame.truth || frame.depth.empty() || frame.body_index.empty() || frame.color.empty()) return out;
  const PartialScanExtractor scans(meta);
  const auto& people = frame.truth->people;
  for (size_t p = 0; p < people.size(); ++p) {
    if (people[p].body_index < 0) continue;
    BodyRef ref;
    ref.key = people[p].tracking_id;
    ref.labels = frame.body_index;
    ref.label = people[p].body_index;
    cv::Mat mask = scans.color_mask(frame, ref);
    if (!mask.empty()) out.emplace_back(static_cast<int>(p), std::move(mask));
  }
  return out;
}

}  // namespace

BoxTruth truth_for_boxes(const RecordingMeta& meta, const RgbdFrame& frame, const std::vector<cv::Rect>& boxes,
                         double min_share, int min_visible_px) {
  BoxTruth out;
  out.person.assign(boxes.size(), -1);
  std::vector<double> best(boxes.size(), 0.0);
  for (const auto& [p, mask] : true_colour_masks(meta, frame)) {
    if (cv::countNonZero(mask) >= min_visible_px) ++out.visible;
    for (size_t i = 0; i < boxes.size(); ++i) {
      const cv::Rect b = boxes[i] & cv::Rect(0, 0, mask.cols, mask.rows);
      if (b.empty()) continue;
      const double share = cv::countNonZero(mask(b)) / static_cast<double>(boxes[i].area());
      if (share >= min_share && share > best[i]) {
        best[i] = share;
        out.person[i] = p;
      }
    }
  }
  return out;
}

std::vector<TrueBody> true_bodies(const RecordingMeta& meta, const RgbdFrame& frame, int min_visible_px) {
  std::vector<TrueBody> out;
  for (const auto& [p, mask] : true_colour_masks(meta, frame)) {
    if (cv::countNonZero(mask) < min_visible_px) continue;
    TrueBody b;
    b.person = p;
    b.track = frame.truth->people[static_cast<size_t>(p)].tracking_id;
    b.box = cv::boundingRect(mask);
    b.mask = mask(b.box).clone();
    out.push_back(std::move(b));
  }
  return out;
}

void ListedDetector::set(const std::vector<cv::Rect>& boxes) {
  next_.clear();
  for (const cv::Rect& b : boxes) next_.push_back({Box{double(b.x), double(b.y), double(b.width), double(b.height)}, 1.0});
}

std::vector<Detection> ListedDetector::detect(const cv::Mat& frame) {
  (void)frame;
  return next_;
}

}  // namespace bodyrec
