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

// The plain rule: together when, over all their common frames, the median distance <= max_distance_m and
// the median speed difference <= max_speed_difference (m/s); no group consistency.
PairScores evaluate_threshold(const WalkingScene& scene, double max_distance_m, double max_speed_difference,
                              double velocity_span_s);

// Choosing and fitting methods (rules, pair models) on scenes: group_selection.h.

}  // namespace bodyrec
