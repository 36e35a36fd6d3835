#include "bodyrec/groups/group_selection.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

std::string number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::string short_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

std::string key(const GroupCandidate& c) {
  return std::to_string(static_cast<int>(c.method)) + "/" + to_string(c.linkage) + "/" + number(c.max_distance_m) +
         "/" + number(c.max_speed_difference) + "/" + c.features.to_string() + "/" + number(c.l2) + "/" +
         number(c.window_s) + "/" + number(c.min_moving_fraction) + "/" + number(c.velocity_span_s);
}

std::string key(const std::vector<size_t>& scenes) {
  std::string s;
  for (size_t i : scenes) s += std::to_string(i) + ",";
  return s;
}

// One scale on the log-odds (fitted to the pairs' labels by 1-D Newton), so that pair_probability means
// something; a positive scale keeps every decision as it is.
void calibrate(PairModel& model, const std::vector<std::pair<double, bool>>& labelled) {
  double scale = 1;
  for (int iteration = 0; iteration < 100; ++iteration) {
    double gradient = 0, curvature = 1e-9;
    for (const auto& [e, together] : labelled) {
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
}

// The windows a pair's final evidence comes from (as window_evidence: those of its last epoch with counted
// windows, or only the last one when `latest`), as (pair, log median distance feature, median speed
// difference) for fast rule fitting.
struct RuleWindow {
  int pair;
  double log_distance, speed_difference;
};
std::vector<RuleWindow> final_rule_windows(const ScenePairs& pairs, const std::vector<PairWindow>& windows,
                                           double min_moving_fraction, bool latest) {
  std::vector<int> last_epoch(pairs.pairs.size(), -1);
  std::vector<size_t> last_window(pairs.pairs.size(), 0);
  for (size_t k = 0; k < windows.size(); ++k)
    if (windows[k].moving_fraction >= min_moving_fraction) {
      last_epoch[windows[k].pair] = windows[k].epoch;
      last_window[windows[k].pair] = k;
    }
  std::vector<RuleWindow> out;
  for (size_t k = 0; k < windows.size(); ++k) {
    const auto& w = windows[k];
    if (w.moving_fraction >= min_moving_fraction && w.epoch == last_epoch[w.pair] && (!latest || k == last_window[w.pair]))
      out.push_back({w.pair, w.x[0], w.x[4]});
  }
  return out;
}

// A fitted model carries the candidate's settings and the scenes it was fitted on.
void take_settings(PairModel& model, const GroupCandidate& c, const std::vector<std::string>& trained_on) {
  model.trained_on = trained_on;
  model.window_s = c.window_s;
  model.velocity_span_s = c.velocity_span_s;
  model.min_moving_fraction = c.min_moving_fraction;
  model.linkage = c.linkage;
}

}  // namespace

std::string describe(const GroupCandidate& c) {
  const std::string window = std::isinf(c.window_s) ? "whole common time" : "window " + short_number(c.window_s) + " s";
  std::string s;
  switch (c.method) {
    case GroupMethod::kRule:
      s = "rule " + short_number(c.max_distance_m) + " m / " + short_number(c.max_speed_difference) + " m/s";
      break;
    case GroupMethod::kLearnedRule:
      s = "learned rule, " + window + ", min-moving " + short_number(c.min_moving_fraction) + ", velocity span " +
          short_number(c.velocity_span_s) + " s";
      break;
    case GroupMethod::kPairModel:
      s = "pair model " + std::to_string(c.features.count()) + " features, L2 " + short_number(c.l2) + ", " + window +
          ", min-moving " + short_number(c.min_moving_fraction) + ", velocity span " + short_number(c.velocity_span_s) +
          " s";
      break;
  }
  return s + ", linkage " + to_string(c.linkage);
}

std::string describe(const FittedGroupMethod& fitted) {
  const std::string base = describe(fitted.candidate);
  if (fitted.candidate.method != GroupMethod::kLearnedRule) return base;
  // "learned rule, ..." -> "learned rule 1.2 m / 0.35 m/s, ..."
  return "learned rule " + short_number(fitted.max_distance_m) + " m / " + short_number(fitted.max_speed_difference) +
         " m/s" + base.substr(std::string("learned rule").size());
}

std::vector<std::pair<double, double>> rule_threshold_grid() {
  std::vector<std::pair<double, double>> grid;
  for (int d = 2; d <= 30; ++d)
    for (int s = 1; s <= 20; ++s) grid.emplace_back(d / 10.0, s / 20.0);
  return grid;
}

PairFeatureSet all_pair_features() { return PairFeatureSet().set(); }

PairFeatureSet distance_speed_features() {
  PairFeatureSet f;
  f.set(0);  // log_median_distance
  f.set(4);  // median_speed_difference
  return f;
}

GroupFamily learned_rule_family(const std::string& name, const GroupGrid& grid) {
  GroupFamily family{name, {}};
  for (GroupLinkage linkage : grid.linkages)
    for (double span : grid.velocity_spans)
      for (double window : grid.windows)
        for (double moving : grid.min_moving) {
          GroupCandidate c;
          c.method = GroupMethod::kLearnedRule;
          c.linkage = linkage;
          c.features = distance_speed_features();
          c.window_s = window;
          c.min_moving_fraction = moving;
          c.velocity_span_s = span;
          family.grid.push_back(c);
        }
  return family;
}

GroupFamily pair_model_family(const std::string& name, PairFeatureSet features, const std::vector<double>& l2,
                              const GroupGrid& grid) {
  GroupFamily family{name, {}};
  for (GroupLinkage linkage : grid.linkages)
    for (double span : grid.velocity_spans)
      for (double window : grid.windows)
        for (double moving : grid.min_moving)
          for (double penalty : l2) {
            GroupCandidate c;
            c.method = GroupMethod::kPairModel;
            c.linkage = linkage;
            c.features = features;
            c.l2 = penalty;
            c.window_s = window;
            c.min_moving_fraction = moving;
            c.velocity_span_s = span;
            family.grid.push_back(c);
          }
  return family;
}

const std::vector<double>& velocity_span_grid() {
  static const std::vector<double> grid = {0.4, 2.0};
  return grid;
}

const std::vector<GroupLinkage>& linkage_grid() {
  static const std::vector<GroupLinkage> grid = {GroupLinkage::kSingle, GroupLinkage::kNone, GroupLinkage::kAverage};
  return grid;
}

std::vector<GroupFamily> standard_group_families() {
  const double whole = std::numeric_limits<double>::infinity();
  const std::vector<double> windows = {8, 5, 12}, moving = {0.5, 0}, l2 = {0.01, 0.1, 1, 3, 10};
  std::vector<GroupFamily> families;
  GroupFamily every{"chosen among all of the above", {}};
  const auto add = [&](const std::string& name, const std::function<GroupFamily(const std::string&,
                                                                                const std::vector<GroupLinkage>&)>& make) {
    families.push_back(make(name + ", linkage none", {GroupLinkage::kNone}));
    families.push_back(make(name + ", linkage single", {GroupLinkage::kSingle}));
    families.push_back(make(name + ", linkage chosen", linkage_grid()));
    const auto& all = families.back().grid;
    every.grid.insert(every.grid.end(), all.begin(), all.end());
  };
  add("plain rule 2.0 m / 0.4 m/s", [](const std::string& name, const std::vector<GroupLinkage>& linkages) {
    GroupFamily f{name, {}};
    for (GroupLinkage linkage : linkages) {
      GroupCandidate c;
      c.method = GroupMethod::kRule;
      c.linkage = linkage;
      f.grid.push_back(c);
    }
    return f;
  });
  const auto grid = [&](const std::vector<GroupLinkage>& linkages, std::vector<double> window_list) {
    return GroupGrid{linkages, std::move(window_list), moving, velocity_span_grid()};
  };
  add("learned rule, whole common time", [&](const std::string& name, const std::vector<GroupLinkage>& linkages) {
    return learned_rule_family(name, grid(linkages, {whole}));
  });
  add("learned rule, windows", [&](const std::string& name, const std::vector<GroupLinkage>& linkages) {
    return learned_rule_family(name, grid(linkages, windows));
  });
  add("pair model, distance + speed difference", [&](const std::string& name, const std::vector<GroupLinkage>& linkages) {
    return pair_model_family(name, distance_speed_features(), l2, grid(linkages, windows));
  });
  add("pair model, all features", [&](const std::string& name, const std::vector<GroupLinkage>& linkages) {
    return pair_model_family(name, all_pair_features(), l2, grid(linkages, windows));
  });
  families.push_back(every);
  return families;
}

GroupFamily default_group_family() {
  for (auto& f : standard_group_families())
    if (f.name == "learned rule, whole common time, linkage chosen") return f;
  throw ProcessingError("no default group family");
}

GroupSelection::GroupSelection(std::vector<WalkingScene> scenes, double velocity_span_s)
    : scenes_(std::move(scenes)), velocity_span_s_(velocity_span_s), pairs_(scenes_.size()) {
  if (scenes_.empty()) throw UsageError("group selection needs at least one scene");
  if (!(velocity_span_s > 0)) throw UsageError("group selection: velocity span must be > 0");
}

const ScenePairs& GroupSelection::pairs(size_t scene) {
  if (!pairs_.at(scene)) pairs_[scene] = std::make_unique<ScenePairs>(scene_pairs(scenes_[scene], velocity_span_s_));
  return *pairs_[scene];
}

const std::vector<PairWindow>& GroupSelection::windows(size_t scene, double window_s, double velocity_span_s) {
  const auto k = std::make_tuple(scene, window_s, velocity_span_s);
  auto it = windows_.find(k);
  if (it == windows_.end()) {
    GroupOptions options;
    options.window_s = window_s;
    options.velocity_span_s = velocity_span_s;
    it = windows_.emplace(k, scene_windows(scenes_.at(scene), pairs(scene), options)).first;
  }
  return it->second;
}

std::vector<double> GroupSelection::evidence(const FittedGroupMethod& fitted, size_t scene) {
  if (!fitted.model)
    return rule_evidence(pairs(scene), fitted.max_distance_m, fitted.max_speed_difference);
  const PairModel& m = *fitted.model;
  return window_evidence(pairs(scene), windows(scene, m.window_s, m.velocity_span_s), m, m.min_moving_fraction);
}

PairScores GroupSelection::score(const FittedGroupMethod& fitted, size_t scene) {
  return score_evidence(pairs(scene), evidence(fitted, scene), fitted.candidate.linkage);
}

const FittedGroupMethod& GroupSelection::fit(const GroupCandidate& c, const std::vector<size_t>& training) {
  if (training.empty()) throw UsageError("fitting a group method needs at least one scene");
  const std::string k = key(c) + "|" + key(training);
  if (const auto it = fits_.find(k); it != fits_.end()) return it->second;
  FittedGroupMethod f;
  f.candidate = c;
  for (size_t s : training) f.trained_on.push_back(scenes_.at(s).name);
  std::sort(f.trained_on.begin(), f.trained_on.end());
  f.max_distance_m = c.max_distance_m;
  f.max_speed_difference = c.max_speed_difference;

  if (c.method == GroupMethod::kLearnedRule) {
    PairModel model;
    model.rule = true;
    model.features = distance_speed_features();
    model.scale.fill(1.0);
    model.weights[0] = 1;
    take_settings(model, c, f.trained_on);
    // Each pair's evidence is the mean vote (+1 / -1) of its final windows: found once per scene, then
    // scored for every pair of thresholds (the same arithmetic as window_evidence, so the same evidence).
    std::vector<std::vector<RuleWindow>> final;
    for (size_t s : training)
      final.push_back(final_rule_windows(pairs(s), windows(s, c.window_s, c.velocity_span_s), c.min_moving_fraction,
                                         std::isinf(c.window_s)));
    double best = -1;
    std::vector<std::vector<double>> best_evidence;
    for (const auto& [distance, speed] : rule_threshold_grid()) {
      const double log_distance = std::log(distance + 0.1);
      double sum = 0;
      std::vector<std::vector<double>> evidence;
      for (size_t i = 0; i < training.size(); ++i) {
        const ScenePairs& p = pairs(training[i]);
        std::vector<double> votes(p.pairs.size(), 0), count(p.pairs.size(), 0);
        for (const auto& w : final[i]) {
          votes[w.pair] += w.log_distance <= log_distance && w.speed_difference <= speed ? 1.0 : -1.0;
          count[w.pair] += 1;
        }
        std::vector<double> e(p.pairs.size(), std::numeric_limits<double>::quiet_NaN());
        for (size_t q = 0; q < e.size(); ++q)
          if (count[q] > 0) e[q] = votes[q] / count[q];
        sum += score_evidence(p, e, c.linkage).f1;
        evidence.push_back(std::move(e));
      }
      if (sum > best + 1e-12) {
        best = sum;
        model.max_distance_m = distance;
        model.max_speed_difference = speed;
        best_evidence = std::move(evidence);
      }
    }
    std::vector<std::pair<double, bool>> labelled;
    for (size_t i = 0; i < training.size(); ++i) {
      const ScenePairs& p = pairs(training[i]);
      for (size_t q = 0; q < p.pairs.size(); ++q)
        if (!std::isnan(best_evidence[i][q])) labelled.emplace_back(best_evidence[i][q], p.labelled[q] != 0);
    }
    calibrate(model, labelled);
    // A power of two: sums of +-weights[0] stay exact, so a pair with as many votes each way is at 0.
    model.weights[0] = std::exp2(std::round(std::log2(model.weights[0])));
    f.max_distance_m = model.max_distance_m;
    f.max_speed_difference = model.max_speed_difference;
    f.model = std::make_shared<const PairModel>(std::move(model));
  } else if (c.method == GroupMethod::kPairModel) {
    // The logistic regression does not depend on the linkage: shared between candidates.
    const std::string lk = c.features.to_string() + "/" + number(c.l2) + "/" + number(c.window_s) + "/" +
                           number(c.min_moving_fraction) + "/" + number(c.velocity_span_s) + "|" + key(training);
    auto& logistic = logistic_[lk];
    if (!logistic) {
      std::vector<PairExample> examples;
      for (size_t s : training) {
        const auto more = window_examples(pairs(s), windows(s, c.window_s, c.velocity_span_s), c.min_moving_fraction);
        examples.insert(examples.end(), more.begin(), more.end());
      }
      logistic = std::make_shared<const PairModel>(train_pair_model(examples, c.l2, c.features));
    }
    PairModel model = *logistic;
    take_settings(model, c, f.trained_on);

    // The decision threshold: evidence is a (weighted) mean of log-odds, so shifting the bias shifts every
    // pair's evidence by the same amount; pick the shift with the best mean F1 on the training scenes.
    std::vector<std::vector<double>> evidence;
    for (size_t s : training)
      evidence.push_back(
          window_evidence(pairs(s), windows(s, c.window_s, c.velocity_span_s), model, c.min_moving_fraction));
    double best_shift = 0, best_f1 = -1;
    for (int step = -40; step <= 40; ++step) {
      const double shift = 0.1 * step;
      double f1 = 0;
      for (size_t i = 0; i < training.size(); ++i) f1 += score_evidence(pairs(training[i]), evidence[i], c.linkage, shift).f1;
      if (f1 > best_f1 + 1e-12) {
        best_f1 = f1;
        best_shift = shift;
      }
    }
    model.bias += best_shift;

    std::vector<std::pair<double, bool>> labelled;
    for (size_t i = 0; i < training.size(); ++i) {
      const ScenePairs& p = pairs(training[i]);
      for (size_t q = 0; q < p.pairs.size(); ++q)
        if (!std::isnan(evidence[i][q])) labelled.emplace_back(evidence[i][q] + best_shift, p.labelled[q] != 0);
    }
    calibrate(model, labelled);
    f.model = std::make_shared<const PairModel>(std::move(model));
  }
  return fits_.emplace(k, std::move(f)).first->second;
}

double GroupSelection::inner_f1(const GroupCandidate& c, const std::vector<size_t>& training) {
  if (training.size() < 2) throw UsageError("leave-one-scene-out needs at least two scenes");
  const std::string k = key(c) + "|" + key(training);
  if (const auto it = inner_.find(k); it != inner_.end()) return it->second;
  double sum = 0;
  for (size_t out : training) {
    std::vector<size_t> rest;
    for (size_t s : training)
      if (s != out) rest.push_back(s);
    sum += score(fit(c, rest), out).f1;
  }
  return inner_[k] = sum / training.size();
}

GroupCandidate GroupSelection::choose(const GroupFamily& family, const std::vector<size_t>& training, double* f1) {
  if (family.grid.empty()) throw UsageError("group family '" + family.name + "' has no candidate");
  if (f1) *f1 = 0;
  if (training.size() < 2 || family.grid.size() == 1) return family.grid.front();
  GroupCandidate best = family.grid.front();
  double best_f1 = -1;
  for (const auto& c : family.grid) {
    const double v = inner_f1(c, training);
    if (v > best_f1 + 1e-12) {
      best_f1 = v;
      best = c;
    }
  }
  if (f1) *f1 = best_f1;
  return best;
}

const FittedGroupMethod& GroupSelection::select_and_fit(const GroupFamily& family, const std::vector<size_t>& training) {
  return fit(choose(family, training), training);
}

NestedResult GroupSelection::nested_loso(const GroupFamily& family) {
  if (scenes_.size() < 3)
    throw UsageError("nested leave-one-scene-out needs at least 3 scenes, got " + std::to_string(scenes_.size()));
  NestedResult result;
  result.family = family.name;
  double sum = 0;
  for (size_t out = 0; out < scenes_.size(); ++out) {
    std::vector<size_t> training;
    for (size_t s = 0; s < scenes_.size(); ++s)
      if (s != out) training.push_back(s);
    NestedFold fold;
    fold.scene = scenes_[out].name;
    fold.chosen = choose(family, training, &fold.inner_f1);
    const FittedGroupMethod& fitted = fit(fold.chosen, training);
    fold.fitted = describe(fitted);
    fold.scores = score(fitted, out);
    sum += fold.scores.f1;
    result.folds.push_back(fold);
  }
  result.mean_f1 = sum / scenes_.size();
  return result;
}

}  // namespace bodyrec
