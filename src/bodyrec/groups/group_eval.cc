#include "bodyrec/groups/group_eval.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

std::map<int, std::vector<const ObsmatRow*>> rows_by_frame(const WalkingScene& scene) {
  std::map<int, std::vector<const ObsmatRow*>> frames;
  for (const auto& r : scene.rows) frames[r.frame].push_back(&r);
  return frames;
}

// A model that ignores its input: lets the replay run before any model exists (training).
std::shared_ptr<const PairModel> blank_model(const GroupOptions& options) {
  auto m = std::make_shared<PairModel>();
  m->scale.fill(1.0);
  m->window_s = options.window_s;
  m->velocity_span_s = options.velocity_span_s;
  return m;
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
  std::map<int, PersonHistory> people;
  long step = 0;
  for (const auto& [frame, rows] : rows_by_frame(scene)) {
    ++step;
    for (const ObsmatRow* r : rows)
      people[r->person].add(step, frame * scene.seconds_per_frame, r->position, velocity_span_s);
  }
  const double all = std::numeric_limits<double>::infinity();
  return score_pairs(scene, [&](int a, int b) {
    const auto f = pair_features(people.at(a), people.at(b), all, all);
    return f && f->median_distance <= max_distance_m && f->median_speed_difference <= max_speed_difference;
  });
}

std::vector<PairExample> training_examples(const WalkingScene& scene, const GroupOptions& options) {
  GroupOptions blank = options;
  blank.model = blank_model(options);
  GroupMembership groups(blank);
  std::vector<PairExample> examples;
  std::map<std::pair<int, int>, std::vector<size_t>> of_pair;
  replay_scene(scene, groups, [&](const std::vector<int>& present) {
    for (size_t i = 0; i < present.size(); ++i)
      for (size_t j = i + 1; j < present.size(); ++j)
        if (const auto f = groups.window_features(present[i], present[j]); f && groups.counts(*f)) {
          PairExample e;
          e.x = f->values;
          e.together = scene.together(present[i], present[j]);
          of_pair[std::minmax(present[i], present[j])].push_back(examples.size());
          examples.push_back(e);
        }
  });
  for (const auto& [pair, list] : of_pair)
    for (size_t k : list) examples[k].weight = 1.0 / list.size();
  return examples;
}

PairModel train_group_model(const std::vector<WalkingScene>& scenes, const GroupOptions& options, double l2) {
  if (scenes.empty()) throw UsageError("training group membership needs at least one scene");
  std::vector<PairExample> examples;
  for (const auto& scene : scenes) {
    const auto more = training_examples(scene, options);
    examples.insert(examples.end(), more.begin(), more.end());
  }
  PairModel model = train_pair_model(examples, l2);
  model.window_s = options.window_s;
  model.velocity_span_s = options.velocity_span_s;
  for (const auto& scene : scenes) model.trained_on.push_back(scene.name);
  std::sort(model.trained_on.begin(), model.trained_on.end());

  // The decision threshold: evidence is a (weighted) mean of log-odds, so shifting the bias shifts every
  // pair's evidence by the same amount; pick the shift with the best mean F1 on the training scenes.
  GroupOptions with_model = options;
  with_model.model = std::make_shared<const PairModel>(model);
  std::vector<std::map<std::pair<int, int>, double>> evidence;
  for (const auto& scene : scenes) evidence.push_back(replay_evidence(scene, with_model));
  double best_shift = 0, best_f1 = -1;
  for (int k = -40; k <= 40; ++k) {
    const double shift = 0.1 * k;
    double f1 = 0;
    for (size_t s = 0; s < scenes.size(); ++s) f1 += evaluate_learned(scenes[s], evidence[s], options.linkage, shift).f1;
    if (f1 > best_f1 + 1e-12) {
      best_f1 = f1;
      best_shift = shift;
    }
  }
  model.bias += best_shift;

  // Calibration: one scale on the log-odds (fitted to the pairs' labels by 1-D Newton), so that
  // pair_probability means something; a positive scale keeps every decision as it is.
  std::vector<std::pair<double, bool>> pairs;
  for (size_t s = 0; s < scenes.size(); ++s)
    for (const auto& [pair, value] : evidence[s])
      pairs.emplace_back(value + best_shift, scenes[s].together(pair.first, pair.second));
  double scale = 1;
  for (int iteration = 0; iteration < 100; ++iteration) {
    double gradient = 0, curvature = 1e-9;
    for (const auto& [e, together] : pairs) {
      const double p = 1 / (1 + std::exp(-scale * e));
      gradient += e * ((together ? 1.0 : 0.0) - p);
      curvature += e * e * p * (1 - p);
    }
    const double step = gradient / curvature;
    scale = std::clamp(scale + step, 1e-3, 1e3);
    if (std::abs(step) < 1e-10 * scale) break;
  }
  for (double& w : model.weights) w *= scale;
  model.bias *= scale;
  return model;
}

double choose_l2(const std::vector<WalkingScene>& scenes, const GroupOptions& options,
                 const std::vector<double>& candidates) {
  if (candidates.empty()) throw UsageError("choose_l2 needs at least one candidate");
  if (scenes.size() < 2 || candidates.size() == 1) return candidates.front();
  double best = candidates.front(), best_f1 = -1;
  for (double l2 : candidates) {
    double f1 = 0;
    for (size_t out = 0; out < scenes.size(); ++out) {
      std::vector<WalkingScene> training;
      for (size_t s = 0; s < scenes.size(); ++s)
        if (s != out) training.push_back(scenes[s]);
      GroupOptions with_model = options;
      with_model.model = std::make_shared<const PairModel>(train_group_model(training, options, l2));
      f1 += evaluate_learned(scenes[out], replay_evidence(scenes[out], with_model), options.linkage).f1;
    }
    if (f1 > best_f1 + 1e-12) {
      best_f1 = f1;
      best = l2;
    }
  }
  return best;
}

}  // namespace bodyrec
