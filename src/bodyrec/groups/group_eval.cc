#include "bodyrec/groups/group_eval.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bodyrec/core/error.h"
#include "bodyrec/groups/pair_windows.h"

namespace bodyrec {
namespace {

std::map<int, std::vector<const ObsmatRow*>> rows_by_frame(const WalkingScene& scene) {
  std::map<int, std::vector<const ObsmatRow*>> frames;
  for (const auto& r : scene.rows) frames[r.frame].push_back(&r);
  return frames;
}

}  // namespace

std::set<std::pair<int, int>> co_present_pairs(const WalkingScene& scene) {
  std::set<std::pair<int, int>> pairs;
  for (const auto& [frame, rows] : rows_by_frame(scene))
    for (size_t i = 0; i < rows.size(); ++i)
      for (size_t j = i + 1; j < rows.size(); ++j)
        pairs.insert(std::minmax(rows[i]->person, rows[j]->person));
  return pairs;
}

PairScores score_pairs(const WalkingScene& scene, const std::function<bool(int, int)>& together) {
  PairScores s;
  for (const auto& [a, b] : co_present_pairs(scene)) {
    ++s.pairs;
    const bool truth = scene.together(a, b), predicted = together(a, b);
    s.labelled_pairs += truth;
    s.predicted_pairs += predicted;
    s.true_pairs += truth && predicted;
  }
  s.precision = s.predicted_pairs ? double(s.true_pairs) / s.predicted_pairs : 0.0;
  s.recall = s.labelled_pairs ? double(s.true_pairs) / s.labelled_pairs : 0.0;
  s.f1 = s.precision + s.recall > 0 ? 2 * s.precision * s.recall / (s.precision + s.recall) : 0.0;
  return s;
}

void replay_scene(const WalkingScene& scene, GroupMembership& groups,
                  const std::function<void(const std::vector<int>& present)>& after) {
  for (const auto& [frame, rows] : rows_by_frame(scene)) {
    std::vector<std::pair<int, cv::Point2d>> positions;
    std::vector<int> present;
    for (const ObsmatRow* r : rows) {
      positions.emplace_back(r->person, r->position * groups.options().units_per_metre);
      present.push_back(r->person);
    }
    groups.update(frame * scene.seconds_per_frame, positions);
    after(present);
  }
}

std::map<std::pair<int, int>, double> replay_evidence(const WalkingScene& scene, const GroupOptions& options) {
  GroupMembership groups(options);
  std::map<std::pair<int, int>, double> evidence;
  replay_scene(scene, groups, [&](const std::vector<int>& present) {
    for (size_t i = 0; i < present.size(); ++i)
      for (size_t j = i + 1; j < present.size(); ++j)
        if (const auto e = groups.pair_evidence(present[i], present[j]))
          evidence[std::minmax(present[i], present[j])] = *e;
  });
  return evidence;
}

PairScores evaluate_learned(const WalkingScene& scene, const std::map<std::pair<int, int>, double>& evidence,
                            GroupLinkage linkage, double shift) {
  std::map<std::pair<int, int>, double> shifted;
  for (const auto& [pair, value] : evidence) shifted[pair] = value + shift;
  if (linkage == GroupLinkage::kNone)
    return score_pairs(scene, [&](int a, int b) {
      const auto it = shifted.find(std::minmax(a, b));
      return it != shifted.end() && it->second > 0;
    });
  std::vector<int> ids;
  for (const auto& r : scene.rows) ids.push_back(r.person);
  std::map<int, size_t> cluster_of;
  const auto clusters = cluster_pairs(ids, shifted, linkage);
  for (size_t c = 0; c < clusters.size(); ++c)
    for (int id : clusters[c]) cluster_of[id] = c;
  return score_pairs(scene, [&](int a, int b) { return cluster_of.at(a) == cluster_of.at(b); });
}

PairScores evaluate_threshold(const WalkingScene& scene, double max_distance_m, double max_speed_difference,
                              double velocity_span_s) {
  const ScenePairs pairs = scene_pairs(scene, velocity_span_s);
  return score_evidence(pairs, rule_evidence(pairs, max_distance_m, max_speed_difference), GroupLinkage::kNone);
}

}  // namespace bodyrec
