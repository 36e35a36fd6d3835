// What scoring and training group membership need from a walking-group scene, computed once: the pairs of
// people seen in a common frame with their labels, the plain rule's statistics per pair, and every window
// of pair features GroupMembership computes while the scene is replayed. Scoring a pair model from these
// gives exactly what replaying the scene through GroupMembership gives (evaluate_learned of
// replay_evidence), without replaying: model selection scores thousands of models.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "bodyrec/groups/group_eval.h"

namespace bodyrec {

struct ScenePairs {
  std::string name;                          // the scene's name
  std::vector<int> ids;                      // everyone in the scene, sorted
  std::vector<std::pair<int, int>> pairs;    // co-present pairs (smaller, larger), sorted
  std::vector<char> labelled;                // per pair: together in groups.txt
  // The plain rule's statistics per pair over all their common frames; has_rule_statistics is 0 when
  // fewer than 2 common samples have velocities (such a pair is never together by the rule).
  std::vector<char> has_rule_statistics;
  std::vector<double> median_distance;          // metres
  std::vector<double> median_speed_difference;  // m/s

  // Index of a co-present pair in `pairs` (a, b in any order), or -1.
  int index(int a, int b) const;
};

// REQUIRES velocity_span_s > 0 (the rule's speeds).
ScenePairs scene_pairs(const WalkingScene& scene, double velocity_span_s);

// One window of a pair's features, at one frame of the replay where both were seen.
struct PairWindow {
  int pair = 0;    // index into ScenePairs::pairs
  int epoch = 0;   // counts how often the pair's evidence was reset (one of the two forgotten and back)
  double moving_fraction = 0;
  PairFeatureVector x{};
};

// Every pair window of a replay through GroupMembership with `options` (window_s, velocity_span_s,
// units_per_metre, forget_after_s; the model and min_moving_fraction play no part), in replay order.
std::vector<PairWindow> scene_windows(const WalkingScene& scene, const ScenePairs& pairs, const GroupOptions& options);

// Each pair's evidence under `model` as GroupMembership keeps it with no half-life: the mean log-odds of
// its windows with moving_fraction >= min_moving_fraction since its last reset (with an infinite
// model.window_s, the latest such window's); NaN for a pair with no such window. `windows` must come
// from scene_windows with the model's window.
std::vector<double> window_evidence(const ScenePairs& pairs, const std::vector<PairWindow>& windows,
                                    const PairModel& model, double min_moving_fraction);

// The training examples of training_examples(): the windows with moving_fraction >= min_moving_fraction,
// each pair weighing 1 in total.
std::vector<PairExample> window_examples(const ScenePairs& pairs, const std::vector<PairWindow>& windows,
                                         double min_moving_fraction);

// The plain rule as evidence: +1 for a pair whose median distance <= max_distance_m and median speed
// difference <= max_speed_difference, -1 for the other pairs with statistics, NaN without.
std::vector<double> rule_evidence(const ScenePairs& pairs, double max_distance_m, double max_speed_difference);

// Scores per-pair evidence (NaN = unknown) plus `shift` the way evaluate_learned does: kNone, a pair is
// together when its evidence > 0; otherwise when cluster_pairs puts both in one cluster.
PairScores score_evidence(const ScenePairs& pairs, const std::vector<double>& evidence, GroupLinkage linkage,
                          double shift = 0);

}  // namespace bodyrec
