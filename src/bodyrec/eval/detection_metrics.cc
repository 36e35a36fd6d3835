#include "bodyrec/eval/detection_metrics.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace bodyrec {

void DetectionEvaluator::add_frame(const std::vector<Detection>& detections,
                                   const std::vector<LabelledBox>& truth) {
  ++frames_;
  frame_begin_.push_back(scored_.size());
  std::vector<size_t> order(detections.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return detections[a].score > detections[b].score; });
  std::vector<bool> taken(truth.size(), false);
  int frame_truth = 0;
  for (const auto& t : truth) frame_truth += t.ignore ? 0 : 1;
  ground_truth_ += frame_truth;
  frame_truth_.push_back(frame_truth);
  for (size_t i : order) {
    const Detection& d = detections[i];
    double best = iou_threshold_;
    int best_index = -1;
    for (size_t g = 0; g < truth.size(); ++g) {
      if (taken[g] || truth[g].ignore) continue;
      const double o = iou(d.box, truth[g].box);
      if (o >= best) {
        best = o;
        best_index = static_cast<int>(g);
      }
    }
    if (best_index >= 0) {
      taken[best_index] = true;
      scored_.push_back({d.score, true});
      continue;
    }
    const bool on_ignored = std::any_of(truth.begin(), truth.end(), [&](const LabelledBox& t) {
      return t.ignore && iou(d.box, t.box) >= iou_threshold_;
    });
    if (!on_ignored) scored_.push_back({d.score, false});
  }
}

DetectionScores DetectionEvaluator::scores() const {
  DetectionScores s;
  s.frames = frames_;
  s.ground_truth = ground_truth_;
  s.detections = static_cast<int>(scored_.size());
  std::vector<std::pair<double, bool>> ranked;
  for (const auto& x : scored_) {
    ranked.emplace_back(x.score, x.true_positive);
    (x.true_positive ? s.true_positives : s.false_positives)++;
  }
  s.precision = s.detections > 0 ? double(s.true_positives) / s.detections : 0.0;
  s.recall = ground_truth_ > 0 ? double(s.true_positives) / ground_truth_ : 0.0;
  s.ap = average_precision(std::move(ranked), ground_truth_);
  return s;
}

std::pair<double, double> DetectionEvaluator::ap_interval(int resamples, double level,
                                                          unsigned long long seed) const {
  if (frames_ == 0 || resamples < 1) return {0.0, 0.0};
  std::mt19937_64 random(seed);
  std::uniform_int_distribution<size_t> pick(0, static_cast<size_t>(frames_) - 1);
  std::vector<double> aps;
  std::vector<std::pair<double, bool>> ranked;
  for (int r = 0; r < resamples; ++r) {
    ranked.clear();
    int truth = 0;
    for (int f = 0; f < frames_; ++f) {
      const size_t frame = pick(random);
      truth += frame_truth_[frame];
      const size_t end = frame + 1 < frame_begin_.size() ? frame_begin_[frame + 1] : scored_.size();
      for (size_t i = frame_begin_[frame]; i < end; ++i) ranked.emplace_back(scored_[i].score, scored_[i].true_positive);
    }
    aps.push_back(average_precision(ranked, truth));
  }
  std::sort(aps.begin(), aps.end());
  const double tail = (1 - level) / 2;
  auto at = [&](double q) { return aps[static_cast<size_t>(std::lround(q * static_cast<double>(aps.size() - 1)))]; };
  return {at(tail), at(1 - tail)};
}

double average_precision(std::vector<std::pair<double, bool>> ranked, int ground_truth) {
  if (ground_truth <= 0 || ranked.empty()) return 0.0;
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<double> precision(ranked.size()), recall(ranked.size());
  int tp = 0;
  for (size_t i = 0; i < ranked.size(); ++i) {
    tp += ranked[i].second ? 1 : 0;
    precision[i] = double(tp) / double(i + 1);
    recall[i] = double(tp) / ground_truth;
  }
  // Precision envelope: the best precision at this recall or any higher one.
  for (size_t i = ranked.size() - 1; i > 0; --i) precision[i - 1] = std::max(precision[i - 1], precision[i]);
  double ap = 0.0, previous_recall = 0.0;
  for (size_t i = 0; i < ranked.size(); ++i) {
    ap += (recall[i] - previous_recall) * precision[i];
    previous_recall = recall[i];
  }
  return ap;
}

}  // namespace bodyrec
