// The learned pair classifier: L2-regularised logistic regression on standardised pair features (one
// window -> log-odds that the two walk together). Small enough to ship as text inside the program
// (pair_model_builtin.cc), reproducible by `bodyrec train-groups` (see the README).
#pragma once

#include <string>
#include <vector>

#include "bodyrec/groups/pair_features.h"

namespace bodyrec {

struct PairModel {
  std::vector<std::string> trained_on;  // scene names, e.g. {"seq_hotel", "zara01"}
  double window_s = 0;                  // feature window it was trained with (GroupOptions::window_s)
  double velocity_span_s = 0;           // and velocity span
  double l2 = 0;                        // and L2 penalty (recorded so training can be reproduced)
  PairFeatureVector mean{};             // standardisation: (x - mean) / scale
  PairFeatureVector scale{};
  PairFeatureVector weights{};
  double bias = 0;                      // includes the decision threshold: logit > 0 means "together"

  // Log-odds of "together" for one window's features.
  double logit(const PairFeatureVector& x) const;
  bool trained_on_scene(const std::string& scene) const;
};

// Text form: "bodyrec-pair-model 1" then lines `key values...` (trained_on, window_s, velocity_span_s, l2,
// mean, scale, weights, bias), numbers with 9 significant digits.
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

// Fits weights and bias by Newton's method (deterministic). `l2` penalises the standardised weights.
// REQUIRES examples of both classes (else ProcessingError). Leaves trained_on, window_s and
// velocity_span_s for the caller.
PairModel train_pair_model(const std::vector<PairExample>& examples, double l2);

// Models shipped in the program: one trained on all three walking-group scenes and one per held-out scene.
const std::vector<PairModel>& builtin_pair_models();
// The built-in model trained on the most scenes that do not include `scene` (so scoring a scene never uses
// a model that saw it); for any other scene name, the model trained on all scenes.
const PairModel& builtin_pair_model_for(const std::string& scene);

}  // namespace bodyrec
