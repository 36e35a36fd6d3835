// Model selection for group membership that never looks at the scene it is scored on. A method family
// (the plain rule, the rule with learned thresholds, a logistic pair model on some features) has a grid
// of candidates (thresholds, linkage, L2 penalty, feature window, min-moving share); the candidate is
// chosen by leave-one-scene-out *within* the training scenes, then fitted on all of them. Nested
// leave-one-scene-out scores each scene with what that procedure gives when the scene is held out.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "bodyrec/groups/pair_windows.h"

namespace bodyrec {

enum class GroupMethod {
  kRule,         // median distance <= max_distance_m and median speed difference <= max_speed_difference
                 // over all the pair's common frames (the plain rule; offline: needs whole trajectories)
  kLearnedRule,  // a rule model (PairModel::rule): that rule per feature window (an infinite window: over
                 // the common time so far), thresholds chosen on the training scenes
  kPairModel,    // logistic regression on window features
};

// One point of a grid: a method with every setting.
struct GroupCandidate {
  GroupMethod method = GroupMethod::kPairModel;
  GroupLinkage linkage = GroupLinkage::kSingle;
  double max_distance_m = 2.0;       // kRule
  double max_speed_difference = 0.4;  // kRule, m/s
  PairFeatureSet features = PairFeatureSet().set();  // kPairModel
  double l2 = 1;                      // kPairModel
  double window_s = 8;                // kLearnedRule, kPairModel (may be infinite)
  double min_moving_fraction = 0.5;   // kLearnedRule, kPairModel
  double velocity_span_s = 0.4;       // kLearnedRule, kPairModel
};
// E.g. "pair model 2 features, L2 1, window 8 s, min-moving 0.5, linkage single".
std::string describe(const GroupCandidate& candidate);


// A candidate fitted to training scenes.
struct FittedGroupMethod {
  GroupCandidate candidate;
  std::shared_ptr<const PairModel> model;          // kLearnedRule, kPairModel
  double max_distance_m = 0, max_speed_difference = 0;  // the rules: the thresholds used
  std::vector<std::string> trained_on;             // scene names, sorted
};
// describe(candidate) with what fitting chose, e.g. "learned rule 1.2 m / 0.35 m/s, whole common time, ...".
std::string describe(const FittedGroupMethod& fitted);

struct GroupFamily {
  std::string name;
  std::vector<GroupCandidate> grid;  // chosen among in this order; the first of equal scores wins
};

// The learned rule's threshold grid: max distance 0.2, 0.3, ... 3.0 m, then max speed difference 0.05,
// 0.10, ... 1.0 m/s (fitting keeps the first of equal mean F1, i.e. the strictest rule).
std::vector<std::pair<double, double>> rule_threshold_grid();

// The feature sets compared: all features, and only log_median_distance + median_speed_difference.
PairFeatureSet all_pair_features();
PairFeatureSet distance_speed_features();

// The settings a grid spans besides the method's own (L2 for pair models).
struct GroupGrid {
  std::vector<GroupLinkage> linkages;
  std::vector<double> windows;  // seconds, infinite = the whole common time
  std::vector<double> min_moving;
  std::vector<double> velocity_spans;
};
// Grids of one method; the order (linkage, then velocity span, window, min-moving, L2 as listed) is the
// order of preference among equal scores.
GroupFamily learned_rule_family(const std::string& name, const GroupGrid& grid);
GroupFamily pair_model_family(const std::string& name, PairFeatureSet features, const std::vector<double>& l2,
                              const GroupGrid& grid);
// The linkages a "linkage chosen" grid tries: single, none, average.
const std::vector<GroupLinkage>& linkage_grid();

// The velocity spans a grid tries: 0.4 s (the scenes' annotation interval) and 2 s (smooths the jitter
// of tracked boxes at video frame rates).
const std::vector<double>& velocity_span_grid();

// The families of docs/benchmarks.md ("Walking groups"), each with linkage none, single and chosen
// (linkage_grid()), then one whose grid is all of theirs together:
//   plain rule (2.0 m, 0.4 m/s); learned rule over the whole common time (min-moving {0.5, 0} x velocity
//   span); learned rule over windows (window {8, 5, 12} s x min-moving x velocity span); pair model on
//   distance + speed difference and on all features (window x min-moving x velocity span x L2 {0.01,
//   0.1, 1, 3, 10}).
std::vector<GroupFamily> standard_group_families();
// The family `train-groups` and the built-in models use: the learned rule over the whole common time
// with its linkage chosen (the family of standard_group_families() with the best nested
// leave-one-scene-out F1 on the walking-group scenes, docs/benchmarks.md).
GroupFamily default_group_family();

struct NestedFold {
  std::string scene;          // held out
  GroupCandidate chosen;      // by leave-one-scene-out within the other scenes
  double inner_f1 = 0;        // its mean F1 there
  std::string fitted;         // describe() of it fitted on the other scenes
  PairScores scores;          // on the held-out scene, fitted on all the other scenes
};

struct NestedResult {
  std::string family;
  std::vector<NestedFold> folds;  // in scene order
  double mean_f1 = 0;
};

class GroupSelection {
 public:
  // Scenes are referred to by index. velocity_span_s: the plain rule's (kRule) velocity span; the other
  // methods take their candidate's.
  explicit GroupSelection(std::vector<WalkingScene> scenes, double velocity_span_s = 0.4);

  const std::vector<WalkingScene>& scenes() const { return scenes_; }

  // Fits `candidate` on the `training` scenes: kPairModel by logistic regression, then the bias shift
  // (-4, -3.9, ... 4) with the best mean F1 on them, then one scale on the log-odds that calibrates
  // pair_probability; kLearnedRule the grid's thresholds with the best mean F1 on them, then the same
  // calibration (rounded to a power of two). Memoised. Throws ProcessingError when the training scenes
  // lack pairs of either label (kPairModel).
  const FittedGroupMethod& fit(const GroupCandidate& candidate, const std::vector<size_t>& training);
  PairScores score(const FittedGroupMethod& fitted, size_t scene);

  // Mean F1 over the scenes of `training`, each scored by the candidate fitted on the others.
  // REQUIRES training.size() >= 2.
  double inner_f1(const GroupCandidate& candidate, const std::vector<size_t>& training);
  // The grid's candidate with the best inner_f1 (the first of equals); with fewer than 2 training scenes
  // or a one-candidate grid, the first candidate. `f1` receives its inner_f1 (0 when not computed).
  GroupCandidate choose(const GroupFamily& family, const std::vector<size_t>& training, double* f1 = nullptr);
  // choose, then fit on all of `training`.
  const FittedGroupMethod& select_and_fit(const GroupFamily& family, const std::vector<size_t>& training);

  // Every scene scored by select_and_fit on all the others. REQUIRES 3 or more scenes (UsageError).
  NestedResult nested_loso(const GroupFamily& family);

  // Evidence per pair of a scene (NaN = unknown) under a fitted method; the rules give +1 / -1.
  std::vector<double> evidence(const FittedGroupMethod& fitted, size_t scene);

 private:
  const ScenePairs& pairs(size_t scene);
  const std::vector<PairWindow>& windows(size_t scene, double window_s, double velocity_span_s);

  std::vector<WalkingScene> scenes_;
  double velocity_span_s_;
  std::vector<std::unique_ptr<ScenePairs>> pairs_;
  std::map<std::tuple<size_t, double, double>, std::vector<PairWindow>> windows_;
  std::map<std::string, FittedGroupMethod> fits_;
  std::map<std::string, std::shared_ptr<const PairModel>> logistic_;  // before the shift and calibration
  std::map<std::string, double> inner_;
};

}  // namespace bodyrec
