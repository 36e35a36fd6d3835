// Online group membership from trajectories: who walks together, updated every frame from tracked
// positions (ground plane in metres, or image pixels with a pixels-per-metre scale). Each update, every
// pair of people seen in it gets the pair model's log-odds for its features over the last `window_s`
// seconds, or over all its common time so far (pair_features.h). A pair's evidence is the mean of those
// log-odds over the time both were seen (optionally fading with a half-life), or with the whole-time
// window the latest one; groups are the connected components of the pairs with positive evidence (group
// consistency: A-B and B-C together puts A and C together even when A-C alone is weak), or other
// linkages. The default model, a learned rule on median distance and speed difference over the whole
// common time, is the method that scored best in nested leave-one-scene-out (docs/benchmarks.md). The
// offline evaluation (`bodyrec eval groups`) replays ground truth through this class.
#pragma once

#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include <opencv2/core/types.hpp>

#include "bodyrec/groups/pair_features.h"
#include "bodyrec/groups/pair_model.h"

namespace bodyrec {

// The defaults of window_s, velocity_span_s, min_moving_fraction and linkage are the settings of the
// built-in model for new scenes (options_for gives any model's).
struct GroupOptions {
  // Pair features over the last window_s seconds (the model's window). Infinite: over all the pair's
  // common time so far (at most max_history_s), and a pair's evidence is then its latest window's log-odds (the latest window holds
  // all the earlier ones), not their mean.
  double window_s = std::numeric_limits<double>::infinity();
  // The longest history kept and looked at, whatever the window: bounds memory and time for people who
  // stay in view for long (longer than anyone in the walking-group scenes, so their figures hold).
  double max_history_s = 120.0;
  double velocity_span_s = 2.0;   // velocity = displacement over at least this long (the model's span)
  double units_per_metre = 1.0;   // positions are divided by this (pixels per metre for image positions)
  double forget_after_s = 2.0;    // ids not updated for this long are forgotten
  double evidence_half_life_s = 0;  // 0: a pair's evidence is the mean over all its common time
  // Windows in which both walk (faster than 0.3 m/s) for less than this share of the samples add no
  // evidence: groups are found from walking together; people standing near each other (a queue, a tram
  // stop) are not a group by proximity alone. 0 = every window counts.
  double min_moving_fraction = 0.5;
  GroupLinkage linkage = GroupLinkage::kSingle;
  // The pair model; null = the built-in model trained on all walking-group scenes.
  std::shared_ptr<const PairModel> model;

  // Throws UsageError naming the field when a value is out of range (window_s > 0, may be infinite;
  // velocity_span_s, max_history_s, units_per_metre, forget_after_s > 0 and finite; evidence_half_life_s
  // >= 0; min_moving_fraction in [0, 1]).
  void check() const;
};

// `base` with `model` and the settings it was trained with (window_s, velocity_span_s,
// min_moving_fraction, linkage).
GroupOptions options_for(std::shared_ptr<const PairModel> model, GroupOptions base = {});

class GroupMembership {
 public:
  // Throws UsageError for invalid options (GroupOptions::check), ProcessingError if no model is available.
  explicit GroupMembership(GroupOptions options = {});

  // One frame: the positions of the people visible at time t (seconds, increasing from call to call; a
  // time not after the previous one throws UsageError). Ids absent for forget_after_s are forgotten.
  // A track id listed twice throws UsageError.
  void update(double t_seconds, const std::vector<std::pair<int, cv::Point2d>>& positions);

  // Track id -> group id, for people in a group of 2 or more among those remembered (seen within
  // forget_after_s). A group keeps its id while it keeps members: old ids go, greedily, to the new
  // clusters sharing the most members with them; the other clusters get new ids.
  std::map<int, int> group_of() const;
  // The groups (2+ members each, ids sorted), ordered by group id.
  std::vector<std::vector<int>> groups() const;
  // Probability that a and b walk together: logistic of their evidence; 0 when they were never seen
  // together (or one was forgotten).
  double pair_probability(int a, int b) const;
  // Their evidence (mean log-odds, > 0 means together), if they were ever seen together.
  std::optional<double> pair_evidence(int a, int b) const;
  // Features of a and b over the window ending at the last update (at most max_history_s long), if both
  // were in it.
  std::optional<PairFeatures> window_features(int a, int b) const;
  // Whether a window's features add evidence (min_moving_fraction).
  bool counts(const PairFeatures& f) const;
  // Drops a track and its pairs (e.g. when the tracker deletes it).
  void forget(int id);

  // The ids currently remembered (seen within forget_after_s).
  std::vector<int> people() const;
  const GroupOptions& options() const { return options_; }
  const PairModel& model() const { return *model_; }

 private:
  struct Evidence {
    double sum = 0;     // (decayed) sum of window log-odds
    double weight = 0;  // (decayed) count of windows
    double last_t = 0;
  };
  void regroup();
  void drop(int id);    // forget without regrouping
  double span() const;  // seconds of history the features cover: min(window_s, max_history_s)

  GroupOptions options_;
  std::shared_ptr<const PairModel> model_;
  long step_ = 0;
  double last_t_ = 0;
  std::map<int, PersonHistory> people_;
  std::map<std::pair<int, int>, Evidence> evidence_;  // keys (smaller id, larger id)
  std::map<std::pair<int, int>, RunningPairStatistics> running_;  // rule models over the whole common time
  std::map<int, int> group_of_;
  int next_group_id_ = 1;
};

// Clusters `ids` by pair evidence (keys (smaller, larger); pairs without an entry are unknown and neither
// join nor split). Returns clusters of every size (singletons included), each sorted, in order of their
// smallest id. kNone is treated as kSingle.
std::vector<std::vector<int>> cluster_pairs(const std::vector<int>& ids,
                                            const std::map<std::pair<int, int>, double>& evidence,
                                            GroupLinkage linkage);

}  // namespace bodyrec
