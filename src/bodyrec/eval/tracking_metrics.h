// Multi-object tracking scores against ground truth with identities: CLEAR MOT (Bernardin & Stiefelhagen
// 2008: MOTA, MOTP, false positives, misses, identity switches) and the identity scores of Ristani et
// al. 2016 (IDF1, IDP, IDR). Both match boxes at IoU >= iou_threshold (0.5 by default).
#pragma once

#include <map>
#include <utility>
#include <vector>

#include "bodyrec/io/ground_truth.h"

namespace bodyrec {

struct TrackingScores {
  double mota = 0.0;  // 1 - (fn + fp + id_switches) / ground_truth; can be negative; 0 without ground truth
  double motp = 0.0;  // mean IoU of the matched pairs (higher is better); 0 without matches
  double idf1 = 0.0;  // 2 idtp / (2 idtp + idfp + idfn)
  double idp = 0.0;   // idtp / (idtp + idfp)
  double idr = 0.0;   // idtp / (idtp + idfn)
  int fp = 0;           // track boxes matched to no ground truth
  int fn = 0;           // ground-truth boxes matched to no track box
  int id_switches = 0;  // a ground-truth object matched to a different track than at its last match
  int matches = 0;
  int idtp = 0, idfp = 0, idfn = 0;
  int ground_truth = 0;  // non-ignored ground-truth boxes
  int hypotheses = 0;    // track boxes counted (those on ignored ground truth are not)
  int frames = 0;
};

// Accumulates frames, then scores them. Frames are added in time order.
class TrackingEvaluator {
 public:
  explicit TrackingEvaluator(double iou_threshold = 0.5) : iou_threshold_(iou_threshold) {}

  // One frame: the tracker's boxes (`id` = track id, >= 0, unique within the frame) and the ground truth.
  // CLEAR MOT matching: a ground-truth object keeps the track it was matched to last time if they still
  // overlap with IoU >= threshold; the remaining boxes are matched by a Hungarian assignment maximising
  // total IoU among pairs >= threshold. Track boxes left unmatched that overlap an ignored ground-truth
  // box (IoU >= threshold) are dropped from every count. Throws ProcessingError on duplicate ids.
  void add_frame(const std::vector<LabelledBox>& tracks, const std::vector<LabelledBox>& truth);

  // IDF1 takes a global one-to-one assignment of ground-truth ids to track ids maximising the number of
  // frames where the paired boxes overlap with IoU >= threshold (IDTP).
  TrackingScores scores() const;

 private:
  double iou_threshold_;
  std::map<int, int> last_match_;                    // ground-truth id -> track id at its last match
  std::map<std::pair<int, int>, int> overlap_frames_;  // (gt id, track id) -> frames with IoU >= threshold
  std::map<int, int> gt_frames_, track_frames_;      // boxes per id
  int fp_ = 0, fn_ = 0, id_switches_ = 0, matches_ = 0, ground_truth_ = 0, hypotheses_ = 0, frames_ = 0;
  double iou_sum_ = 0.0;
};

}  // namespace bodyrec
