#include "bodyrec/eval/tracking_metrics.h"

#include <set>
#include <string>

#include "bodyrec/core/error.h"
#include "bodyrec/tracking/assignment.h"

namespace bodyrec {

void TrackingEvaluator::add_frame(const std::vector<LabelledBox>& tracks, const std::vector<LabelledBox>& truth) {
  ++frames_;
  std::set<int> seen;
  for (const auto& h : tracks)
    if (!seen.insert(h.id).second)
      throw ProcessingError("tracking evaluation: track id " + std::to_string(h.id) + " appears twice in frame " +
                            std::to_string(h.frame));
  std::vector<int> gts;  // indices of non-ignored ground truth
  for (int g = 0; g < static_cast<int>(truth.size()); ++g)
    if (!truth[g].ignore) gts.push_back(g);
  const int ng = static_cast<int>(gts.size()), nh = static_cast<int>(tracks.size());
  std::vector<std::vector<double>> overlap(ng, std::vector<double>(nh, 0.0));
  for (int i = 0; i < ng; ++i)
    for (int j = 0; j < nh; ++j) overlap[i][j] = iou(truth[gts[i]].box, tracks[j].box);

  std::vector<int> match_of_gt(ng, -1), match_of_track(nh, -1);
  // 1. Keep last frame's correspondences that still hold.
  for (int i = 0; i < ng; ++i) {
    const auto it = last_match_.find(truth[gts[i]].id);
    if (it == last_match_.end()) continue;
    for (int j = 0; j < nh; ++j)
      if (tracks[j].id == it->second && match_of_track[j] < 0 && overlap[i][j] >= iou_threshold_) {
        match_of_gt[i] = j;
        match_of_track[j] = i;
      }
  }
  // 2. Hungarian on the rest.
  std::vector<int> rest_g, rest_h;
  for (int i = 0; i < ng; ++i)
    if (match_of_gt[i] < 0) rest_g.push_back(i);
  for (int j = 0; j < nh; ++j)
    if (match_of_track[j] < 0) rest_h.push_back(j);
  std::vector<std::vector<double>> rest(rest_g.size(), std::vector<double>(rest_h.size(), 0.0));
  for (size_t a = 0; a < rest_g.size(); ++a)
    for (size_t b = 0; b < rest_h.size(); ++b) rest[a][b] = overlap[rest_g[a]][rest_h[b]];
  for (const auto& [a, b] : max_score_assignment(rest, iou_threshold_)) {
    const int i = rest_g[a], j = rest_h[b];
    match_of_gt[i] = j;
    match_of_track[j] = i;
    const auto it = last_match_.find(truth[gts[i]].id);
    if (it != last_match_.end() && it->second != tracks[j].id) ++id_switches_;
  }
  // 3. Count. Unmatched track boxes on ignored ground truth do not count at all.
  std::vector<bool> counted(nh, true);
  for (int j = 0; j < nh; ++j) {
    if (match_of_track[j] >= 0) continue;
    for (const auto& t : truth)
      if (t.ignore && iou(t.box, tracks[j].box) >= iou_threshold_) counted[j] = false;
  }
  for (int i = 0; i < ng; ++i) {
    const int gid = truth[gts[i]].id;
    ++ground_truth_;
    ++gt_frames_[gid];
    if (match_of_gt[i] < 0) {
      ++fn_;
      continue;
    }
    ++matches_;
    iou_sum_ += overlap[i][match_of_gt[i]];
    last_match_[gid] = tracks[match_of_gt[i]].id;
  }
  for (int j = 0; j < nh; ++j) {
    if (!counted[j]) continue;
    ++hypotheses_;
    ++track_frames_[tracks[j].id];
    if (match_of_track[j] < 0) ++fp_;
    // IDF1 counts every overlapping pair, whatever the frame-level matching chose.
    for (int i = 0; i < ng; ++i)
      if (overlap[i][j] >= iou_threshold_) ++overlap_frames_[{truth[gts[i]].id, tracks[j].id}];
  }
}

TrackingScores TrackingEvaluator::scores() const {
  TrackingScores s;
  s.fp = fp_;
  s.fn = fn_;
  s.id_switches = id_switches_;
  s.matches = matches_;
  s.ground_truth = ground_truth_;
  s.hypotheses = hypotheses_;
  s.frames = frames_;
  if (ground_truth_ > 0) s.mota = 1.0 - static_cast<double>(fn_ + fp_ + id_switches_) / ground_truth_;
  if (matches_ > 0) s.motp = iou_sum_ / matches_;

  // Global id assignment over the ids that overlap at all (others cannot contribute).
  std::map<int, int> gt_row, track_col;
  for (const auto& [pair, n] : overlap_frames_) {
    gt_row.emplace(pair.first, static_cast<int>(gt_row.size()));
    track_col.emplace(pair.second, static_cast<int>(track_col.size()));
  }
  std::vector<std::vector<double>> count(gt_row.size(), std::vector<double>(track_col.size(), 0.0));
  for (const auto& [pair, n] : overlap_frames_) count[gt_row[pair.first]][track_col[pair.second]] = n;
  for (const auto& [r, c] : max_score_assignment(count, 0.5)) s.idtp += static_cast<int>(count[r][c]);
  s.idfn = ground_truth_ - s.idtp;
  s.idfp = hypotheses_ - s.idtp;
  if (s.idtp > 0) {
    s.idf1 = 2.0 * s.idtp / (2.0 * s.idtp + s.idfp + s.idfn);
    s.idp = static_cast<double>(s.idtp) / (s.idtp + s.idfp);
    s.idr = static_cast<double>(s.idtp) / (s.idtp + s.idfn);
  }
  return s;
}

}  // namespace bodyrec
