// The pair classifier of group membership: one window of pair features -> log-odds that the two walk
// together. Either L2-regularised logistic regression on standardised features or a learned rule
// (thresholds on median distance and median speed difference). Small enough to ship as text inside the
// program (pair_model_builtin.cc), reproducible by `bodyrec train-groups` (see the README).
#pragma once

#include <string>
#include <vector>

#include "bodyrec/groups/pair_features.h"

namespace bodyrec {

// How pairs become groups.
enum class GroupLinkage {
  kNone,     // offline scoring only: a pair is together when its own evidence is > 0 (no consistency)
  kSingle,   // connected components of the pairs with evidence > 0
  kAverage,  // merge clusters while the mean evidence over their known pairs is > 0
};
const char* to_string(GroupLinkage linkage);

struct PairModel {
  std::vector<std::string> trained_on;  // scene names, e.g. {"seq_hotel", "zara01"}
  double window_s = 0;                  // feature window it was trained with (GroupOptions::window_s; may be
                                        // infinite: the whole common time, text "inf")
  double velocity_span_s = 0;           // and velocity span
  double l2 = 0;                        // and L2 penalty (recorded so training can be reproduced)
  // The rest of the settings it was chosen and trained with (GroupOptions takes them with options_for).
  PairFeatureSet features = PairFeatureSet().set();  // features it uses; the others have weight 0
  double min_moving_fraction = 0.5;
  GroupLinkage linkage = GroupLinkage::kSingle;
  // A rule instead of logistic regression: logit = bias + weights[0] * v, where v = +1 when the window's
  // median distance <= max_distance_m and its median speed difference <= max_speed_difference, else -1
  // (mean and scale play no part).
  bool rule = false;
  double max_distance_m = 0, max_speed_difference = 0;
  PairFeatureVector mean{};             // standardisation: (x - mean) / scale
  PairFeatureVector scale{};
  PairFeatureVector weights{};
  double bias = 0;                      // includes the decision threshold: logit > 0 means "together"

  // Log-odds of "together" for one window's features.
  double logit(const PairFeatureVector& x) const;
  bool trained_on_scene(const std::string& scene) const;
};

// E.g. "learned rule: median distance <= 1.3 m and median speed difference <= 0.2 m/s over the whole common
// time, min-moving 0.5, linkage single" or "logistic regression on 15 features over 8 s windows, ...".
std::string describe(const PairModel& model);

// Text form: "bodyrec-pair-model 1" then lines `key values...` (trained_on, window_s, velocity_span_s, l2,
// features (names), min_moving, linkage (none|single|average), rule (max distance, max speed difference;
// only for a rule), mean, scale, weights, bias), numbers with 9 significant digits. features, min_moving
// and linkage may be missing (then: all, 0.5, single).
std::string to_text(const PairModel& model);
// Throws InputError naming `where` and the line for a wrong header, unknown key, missing key or a value
// count/number that does not fit.
PairModel parse_pair_model(const std::string& text, const std::string& where);
PairModel read_pair_model(const std::string& path);

struct PairExample {
  PairFeatureVector x{};
  bool together = false;
  double weight = 1;  // the trainer gives every pair the same total weight
};

// Fits weights and bias by Newton's method (deterministic). `l2` penalises the standardised weights; the
// features outside `features` get weight 0. REQUIRES examples of both classes (else ProcessingError) and
// at least one feature (else UsageError). Leaves trained_on, window_s, velocity_span_s, min_moving_fraction
// and linkage for the caller.
PairModel train_pair_model(const std::vector<PairExample>& examples, double l2,
                           PairFeatureSet features = PairFeatureSet().set());

// Models shipped in the program: one trained on all three walking-group scenes and one per held-out scene.
const std::vector<PairModel>& builtin_pair_models();
// The built-in model trained on the most scenes that do not include `scene` (so scoring a scene never uses
// a model that saw it); for any other scene name, the model trained on all scenes.
const PairModel& builtin_pair_model_for(const std::string& scene);

}  // namespace bodyrec
