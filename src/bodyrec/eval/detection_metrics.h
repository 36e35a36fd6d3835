// Detection scoring against ground truth: greedy matching at an IoU threshold in decreasing score order
// (PASCAL VOC / COCO style), precision, recall and average precision with all-points interpolation.
#pragma once

#include <map>
#include <utility>
#include <vector>

#include "bodyrec/core/geometry.h"
#include "bodyrec/io/ground_truth.h"

namespace bodyrec {

struct DetectionScores {
  double ap = 0.0;         // area under the interpolated precision-recall curve (all points, VOC 2010+)
  double precision = 0.0;  // at the full set of detections
  double recall = 0.0;
  int true_positives = 0;
  int false_positives = 0;
  int ground_truth = 0;    // non-ignored ground-truth boxes in the scored frames
  int detections = 0;      // detections counted (those matched to ignored boxes are not)
  int frames = 0;
};

// Accumulates per-frame detections and ground truth, then scores them all together (AP ranks every
// detection of every frame by score).
class DetectionEvaluator {
 public:
  explicit DetectionEvaluator(double iou_threshold = 0.5) : iou_threshold_(iou_threshold) {}

  // Adds one frame. Each detection is matched to the unmatched non-ignored ground-truth box of highest
  // IoU >= threshold, detections taken by decreasing score (ties: input order); a detection whose best
  // overlap is an ignored box is dropped from the count.
  void add_frame(const std::vector<Detection>& detections, const std::vector<LabelledBox>& truth);

  DetectionScores scores() const;

  // Percentile bootstrap of the AP over frames: `resamples` draws, each of as many frames as were added,
  // picked with replacement (std::mt19937_64 seeded with `seed`, so the interval is reproducible); returns
  // the central `level` interval of the draws' APs. Frames are the unit, so this is the noise of a figure
  // over independent images; for a video's correlated frames it is too narrow. {0, 0} without frames.
  std::pair<double, double> ap_interval(int resamples, double level = 0.95, unsigned long long seed = 1) const;

 private:
  struct Scored {
    double score;
    bool true_positive;
  };
  double iou_threshold_;
  std::vector<Scored> scored_;
  std::vector<size_t> frame_begin_;    // each frame's first entry in scored_
  std::vector<int> frame_truth_;       // each frame's non-ignored ground-truth boxes
  int ground_truth_ = 0;
  int frames_ = 0;
};

// All-points interpolated average precision from (score, is-true-positive) pairs and the number of
// ground-truth objects. Sorting is by decreasing score, stable.
double average_precision(std::vector<std::pair<double, bool>> ranked, int ground_truth);

}  // namespace bodyrec
