// Offline evaluation and training of group membership on walking-group scenes: ground-truth trajectories
// are replayed frame by frame through GroupMembership (the online code), and every pair of people seen in
// a common frame is scored: together in the labels vs together in the result.
#pragma once

#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "bodyrec/groups/group_membership.h"
#include "bodyrec/groups/walking_scene.h"

namespace bodyrec {

struct PairScores {
  int pairs = 0;           // pairs of people seen in at least one common frame
  int labelled_pairs = 0;  // of those, together in groups.txt
  int predicted_pairs = 0; // of those, together in the result
  int true_pairs = 0;      // both
  double precision = 0, recall = 0, f1 = 0;  // 0 when undefined (nothing predicted / labelled)
};

// The co-present pairs of a scene (keys (smaller, larger)) and their labels.
std::set<std::pair<int, int>> co_present_pairs(const WalkingScene& scene);

// Scores `together` (called for each co-present pair) against the scene's labels.
PairScores score_pairs(const WalkingScene& scene, const std::function<bool(int, int)>& together);

// Feeds the scene's frames (t = frame * seconds_per_frame) to `groups`, calling `after` with the ids of each
// frame after its update.
void replay_scene(const WalkingScene& scene, GroupMembership& groups,
                  const std::function<void(const std::vector<int>& present)>& after);

// Each co-present pair's final evidence (its value when last seen together) from a replay.
std::map<std::pair<int, int>, double> replay_evidence(const WalkingScene& scene, const GroupOptions& options);

// The learned method: replay, then cluster the scene's pair graph (options.linkage); a pair is together
// when both are in one cluster (kNone: when its evidence > 0). `shift` is added to every evidence.
PairScores evaluate_learned(const WalkingScene& scene, const std::map<std::pair<int, int>, double>& evidence,
                            GroupLinkage linkage, double shift = 0);

// The plain rule of issue 11: together when, over all common frames, the median distance <= max_distance_m
// and the median speed difference <= max_speed_difference (m/s).
PairScores evaluate_threshold(const WalkingScene& scene, double max_distance_m, double max_speed_difference,
                              double velocity_span_s);

// One example per pair and frame where both are seen (window features as GroupMembership computes them),
// each pair weighing 1 in total.
std::vector<PairExample> training_examples(const WalkingScene& scene, const GroupOptions& options);

// Trains the pair model on `scenes`: logistic regression on their examples, then the decision threshold
// (a shift of the bias) that maximises the mean pair F1 over these same scenes with options.linkage, then
// one positive scale on the log-odds fitted to the pairs' labels (calibrates pair_probability without
// changing any decision).
PairModel train_group_model(const std::vector<WalkingScene>& scenes, const GroupOptions& options, double l2);

// The L2 penalty from `candidates` whose models, trained leave-one-scene-out within `scenes`, score the best
// mean pair F1 on the scene left out (so the held-out scene of an outer evaluation is never looked at).
// With one scene or one candidate, the first candidate.
double choose_l2(const std::vector<WalkingScene>& scenes, const GroupOptions& options,
                 const std::vector<double>& candidates);

}  // namespace bodyrec
