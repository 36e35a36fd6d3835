#include "bodyrec/groups/pair_windows.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();

// A model that ignores its input: lets the replay run without one.
std::shared_ptr<const PairModel> blank_model() {
  auto m = std::make_shared<PairModel>();
  m->scale.fill(1.0);
  m->window_s = 1;
  m->velocity_span_s = 1;
  return m;
}

PairScores count(const ScenePairs& pairs, const std::vector<char>& predicted) {
  PairScores s;
  for (size_t p = 0; p < pairs.pairs.size(); ++p) {
    ++s.pairs;
    s.labelled_pairs += pairs.labelled[p];
    s.predicted_pairs += predicted[p];
    s.true_pairs += pairs.labelled[p] && predicted[p];
  }
  s.precision = s.predicted_pairs ? double(s.true_pairs) / s.predicted_pairs : 0.0;
  s.recall = s.labelled_pairs ? double(s.true_pairs) / s.labelled_pairs : 0.0;
  s.f1 = s.precision + s.recall > 0 ? 2 * s.precision * s.recall / (s.precision + s.recall) : 0.0;
  return s;
}

}  // namespace

int ScenePairs::index(int a, int b) const {
  const std::pair<int, int> key = std::minmax(a, b);
  const auto it = std::lower_bound(pairs.begin(), pairs.end(), key);
  return it != pairs.end() && *it == key ? static_cast<int>(it - pairs.begin()) : -1;
}

ScenePairs scene_pairs(const WalkingScene& scene, double velocity_span_s) {
  if (!(velocity_span_s > 0)) throw UsageError("scene pairs: velocity span must be > 0");
  ScenePairs out;
  out.name = scene.name;
  const auto co_present = co_present_pairs(scene);
  out.pairs.assign(co_present.begin(), co_present.end());
  std::set<int> ids;
  for (const auto& r : scene.rows) ids.insert(r.person);
  out.ids.assign(ids.begin(), ids.end());

  std::map<int, PersonHistory> people;
  long step = 0;
  int last_frame = -1;
  for (const auto& r : scene.rows) {  // rows are sorted by frame
    if (r.frame != last_frame) ++step;
    last_frame = r.frame;
    people[r.person].add(step, r.frame * scene.seconds_per_frame, r.position, velocity_span_s);
  }
  const double all = std::numeric_limits<double>::infinity();
  const size_t n = out.pairs.size();
  out.labelled.resize(n);
  out.has_rule_statistics.resize(n);
  out.median_distance.assign(n, kUnknown);
  out.median_speed_difference.assign(n, kUnknown);
  for (size_t p = 0; p < n; ++p) {
    const auto [a, b] = out.pairs[p];
    out.labelled[p] = scene.together(a, b);
    if (const auto f = pair_features(people.at(a), people.at(b), all, all)) {
      out.has_rule_statistics[p] = 1;
      out.median_distance[p] = f->median_distance;
      out.median_speed_difference[p] = f->median_speed_difference;
    }
  }
  return out;
}

std::vector<PairWindow> scene_windows(const WalkingScene& scene, const ScenePairs& pairs, const GroupOptions& options) {
  GroupOptions blank = options;
  blank.model = blank_model();
  blank.min_moving_fraction = 0;
  GroupMembership groups(blank);
  std::vector<PairWindow> windows;
  std::map<int, int> incarnation;               // person -> how often (re)appeared after being forgotten
  std::vector<std::pair<int, int>> seen_as(pairs.pairs.size(), {-1, -1});  // incarnations of a pair's window
  std::vector<int> epoch(pairs.pairs.size(), 0);
  std::set<int> remembered;
  replay_scene(scene, groups, [&](const std::vector<int>& present) {
    for (int id : present)
      if (!remembered.count(id)) ++incarnation[id];
    for (size_t i = 0; i < present.size(); ++i)
      for (size_t j = i + 1; j < present.size(); ++j) {
        const auto f = groups.window_features(present[i], present[j]);
        if (!f) continue;
        PairWindow w;
        w.pair = pairs.index(present[i], present[j]);
        if (w.pair < 0) throw ProcessingError("scene windows: the pairs are not this scene's");
        const auto [a, b] = pairs.pairs[w.pair];
        const std::pair<int, int> now{incarnation[a], incarnation[b]};
        if (seen_as[w.pair] != now && seen_as[w.pair].first >= 0) ++epoch[w.pair];
        seen_as[w.pair] = now;
        w.epoch = epoch[w.pair];
        w.moving_fraction = f->moving_fraction;
        w.x = f->values;
        windows.push_back(w);
      }
    const auto people = groups.people();
    remembered.clear();
    remembered.insert(people.begin(), people.end());
  });
  return windows;
}

std::vector<double> window_evidence(const ScenePairs& pairs, const std::vector<PairWindow>& windows,
                                    const PairModel& model, double min_moving_fraction) {
  const size_t n = pairs.pairs.size();
  const bool latest = std::isinf(model.window_s);
  std::vector<double> sum(n, 0), weight(n, 0);
  std::vector<int> epoch(n, -1);
  for (const auto& w : windows) {
    if (!(w.moving_fraction >= min_moving_fraction)) continue;
    if (latest || w.epoch != epoch[w.pair]) {  // GroupMembership starts the pair's evidence again
      sum[w.pair] = 0;
      weight[w.pair] = 0;
      epoch[w.pair] = w.epoch;
    }
    sum[w.pair] += model.logit(w.x);
    weight[w.pair] += 1;
  }
  std::vector<double> evidence(n, kUnknown);
  for (size_t p = 0; p < n; ++p)
    if (weight[p] > 0) evidence[p] = sum[p] / weight[p];
  return evidence;
}

std::vector<PairExample> window_examples(const ScenePairs& pairs, const std::vector<PairWindow>& windows,
                                         double min_moving_fraction) {
  std::vector<PairExample> examples;
  std::vector<int> per_pair(pairs.pairs.size(), 0);
  std::vector<int> pair_of;
  for (const auto& w : windows) {
    if (!(w.moving_fraction >= min_moving_fraction)) continue;
    PairExample e;
    e.x = w.x;
    e.together = pairs.labelled[w.pair];
    examples.push_back(e);
    pair_of.push_back(w.pair);
    ++per_pair[w.pair];
  }
  for (size_t k = 0; k < examples.size(); ++k) examples[k].weight = 1.0 / per_pair[pair_of[k]];
  return examples;
}

std::vector<double> rule_evidence(const ScenePairs& pairs, double max_distance_m, double max_speed_difference) {
  std::vector<double> evidence(pairs.pairs.size(), kUnknown);
  for (size_t p = 0; p < pairs.pairs.size(); ++p)
    if (pairs.has_rule_statistics[p])
      evidence[p] = pairs.median_distance[p] <= max_distance_m &&
                            pairs.median_speed_difference[p] <= max_speed_difference
                        ? 1.0
                        : -1.0;
  return evidence;
}

PairScores score_evidence(const ScenePairs& pairs, const std::vector<double>& evidence, GroupLinkage linkage,
                          double shift) {
  const size_t n = pairs.pairs.size();
  if (evidence.size() != n) throw UsageError("score_evidence: one evidence value per pair is needed");
  std::vector<char> predicted(n, 0);
  if (linkage == GroupLinkage::kAverage) {
    std::map<std::pair<int, int>, double> known;
    for (size_t p = 0; p < n; ++p)
      if (!std::isnan(evidence[p])) known[pairs.pairs[p]] = evidence[p] + shift;
    std::map<int, size_t> cluster_of;
    const auto clusters = cluster_pairs(pairs.ids, known, linkage);
    for (size_t c = 0; c < clusters.size(); ++c)
      for (int id : clusters[c]) cluster_of[id] = c;
    for (size_t p = 0; p < n; ++p) predicted[p] = cluster_of.at(pairs.pairs[p].first) == cluster_of.at(pairs.pairs[p].second);
    return count(pairs, predicted);
  }
  for (size_t p = 0; p < n; ++p) predicted[p] = evidence[p] + shift > 0;  // NaN compares false
  if (linkage == GroupLinkage::kNone) return count(pairs, predicted);
  // Single linkage: connected components of the together pairs (ids indexed by their sorted position).
  std::vector<size_t> parent(pairs.ids.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  auto slot = [&](int id) {
    return static_cast<size_t>(std::lower_bound(pairs.ids.begin(), pairs.ids.end(), id) - pairs.ids.begin());
  };
  for (size_t p = 0; p < n; ++p)
    if (predicted[p]) parent[root(slot(pairs.pairs[p].first))] = root(slot(pairs.pairs[p].second));
  for (size_t p = 0; p < n; ++p)
    predicted[p] = root(slot(pairs.pairs[p].first)) == root(slot(pairs.pairs[p].second));
  return count(pairs, predicted);
}

}  // namespace bodyrec
