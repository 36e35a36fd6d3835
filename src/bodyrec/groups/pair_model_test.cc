// The pair model: training on separable data, the text form and its errors, built-in model choice.
#include "bodyrec/groups/pair_model.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "bodyrec/groups/group_membership.h"
#include "test_support.h"

namespace bodyrec::testing {
namespace {

TEST(PairModel, TrainingSeparatesTogetherFromApartOnFeatureZero) {
  std::vector<PairExample> examples;
  for (int k = 0; k < 40; ++k) {
    PairExample e;
    e.x.fill(0.5);
    e.x[0] = k < 20 ? 0.1 * k : 3 + 0.1 * k;  // together: small log-distance
    e.x[3] = (k % 7) * 0.1;                    // noise
    e.together = k < 20;
    examples.push_back(e);
  }
  const PairModel m = train_pair_model(examples, 0.01);
  EXPECT_LT(m.weights[0], 0);
  PairFeatureVector near = examples[5].x, far = examples[30].x;
  EXPECT_GT(m.logit(near), 2.0);
  EXPECT_LT(m.logit(far), -2.0);
  // Only some features: the others get weight 0.
  PairFeatureSet two;
  two.set(0);
  two.set(3);
  const PairModel sub = train_pair_model(examples, 0.01, two);
  EXPECT_LT(sub.weights[0], 0);
  for (int i = 0; i < kPairFeatureCount; ++i) {
    if (i != 0 && i != 3) {
      EXPECT_EQ(sub.weights[i], 0.0) << i;
    }
  }
  EXPECT_EQ(sub.features, two);
  EXPECT_GT(sub.logit(near), 2.0);
  EXPECT_THROW(train_pair_model(examples, 0.01, PairFeatureSet()), UsageError);
  examples.resize(10);  // one class only
  EXPECT_THROW(train_pair_model(examples, 0.01), ProcessingError);
}

TEST(PairModel, RuleVotesOnMedianDistanceAndSpeedDifference) {
  PairModel m;
  m.rule = true;
  m.max_distance_m = 1.3;
  m.max_speed_difference = 0.2;
  m.weights[0] = 4;
  PairFeatureVector x{};
  x[0] = std::log(1.0 + 0.1);  // median distance 1 m
  x[4] = 0.1;                  // median speed difference
  EXPECT_EQ(m.logit(x), 4.0);
  x[4] = 0.3;
  EXPECT_EQ(m.logit(x), -4.0);
  x[4] = 0.1;
  x[0] = std::log(1.5 + 0.1);
  EXPECT_EQ(m.logit(x), -4.0);
  x[0] = std::log(1.3 + 0.1);  // at the threshold: together
  EXPECT_EQ(m.logit(x), 4.0);
}

TEST(PairModel, TextRoundTripAndBrokenText) {
  PairModel m;
  m.trained_on = {"a", "b"};
  m.window_s = 8;
  m.velocity_span_s = 0.4;
  for (int i = 0; i < kPairFeatureCount; ++i) {
    m.mean[i] = i * 0.25;
    m.scale[i] = 1 + i;
    m.weights[i] = -0.125 * i;
  }
  m.bias = -1.5;
  m.min_moving_fraction = 0.25;
  m.linkage = GroupLinkage::kAverage;
  const PairModel back = parse_pair_model(to_text(m), "m");
  EXPECT_EQ(back.trained_on, m.trained_on);
  EXPECT_EQ(back.weights, m.weights);
  EXPECT_EQ(back.scale, m.scale);
  EXPECT_EQ(back.bias, m.bias);
  EXPECT_EQ(back.features, m.features);
  EXPECT_EQ(back.min_moving_fraction, 0.25);
  EXPECT_EQ(back.linkage, GroupLinkage::kAverage);
  EXPECT_FALSE(back.rule);
  std::string e = input_error([] { parse_pair_model("hello\n", "f.txt"); });
  EXPECT_TRUE(contains(e, "f.txt:1: not a bodyrec pair model")) << e;
  std::string text = to_text(m);
  text.replace(text.find("bias"), 4, "bais");
  e = input_error([&] { parse_pair_model(text, "f.txt"); });
  EXPECT_TRUE(contains(e, "f.txt:12: bais: unknown key")) << e;
  text = to_text(m);
  text.replace(text.find("window_s 8"), 10, "window_s 8 9");
  e = input_error([&] { parse_pair_model(text, "f.txt"); });
  EXPECT_TRUE(contains(e, "f.txt:3: window_s: expected 1 numbers, got 2")) << e;
  e = input_error([] { read_pair_model("/nonexistent/model.txt"); });
  EXPECT_TRUE(contains(e, "no such file")) << e;

  // Settings lines: unknown names and values out of range.
  const auto broken = [&](const std::string& from, const std::string& to) {
    std::string t = to_text(m);
    t.replace(t.find(from), from.size(), to);
    return input_error([&] { parse_pair_model(t, "f.txt"); });
  };
  e = broken("linkage average", "linkage complete");
  EXPECT_TRUE(contains(e, "f.txt:8: linkage: expected none, single or average, got 'complete'")) << e;
  e = broken("features log_median_distance", "features log_median_distance bogus");
  EXPECT_TRUE(contains(e, "f.txt:6: features: unknown feature 'bogus'")) << e;
  e = broken("min_moving 0.25", "min_moving 2");
  EXPECT_TRUE(contains(e, "min_moving is not in [0, 1]")) << e;
  e = broken("velocity_span_s 0.4", "velocity_span_s inf");
  EXPECT_TRUE(contains(e, "f.txt:4: velocity_span_s: not a finite number: 'inf'")) << e;
  e = broken("linkage average", "linkage average\nrule 1.5");
  EXPECT_TRUE(contains(e, "f.txt:9: rule: expected 2 numbers, got 1")) << e;
  e = broken("linkage average", "linkage average\nrule -1 0.2");
  EXPECT_TRUE(contains(e, "f.txt:9: rule: expected a max distance > 0")) << e;
  // A weight on a feature the model does not use.
  PairModel two = m;
  two.features.reset();
  two.features.set(0);
  e = input_error([&] { parse_pair_model(to_text(two), "f.txt"); });
  EXPECT_TRUE(contains(e, "feature log_max_distance is not used but has a weight")) << e;

  // A rule over the whole common time.
  PairModel r;
  r.trained_on = {"a"};
  r.window_s = std::numeric_limits<double>::infinity();
  r.velocity_span_s = 0.4;
  r.rule = true;
  r.max_distance_m = 1.3;
  r.max_speed_difference = 0.2;
  r.features.reset();
  r.features.set(0);
  r.features.set(4);
  r.scale.fill(1);
  r.weights[0] = 4;
  const std::string rule_text = to_text(r);
  EXPECT_TRUE(contains(rule_text, "window_s inf\n")) << rule_text;
  EXPECT_TRUE(contains(rule_text, "rule 1.3 0.2\n")) << rule_text;
  const PairModel rb = parse_pair_model(rule_text, "r");
  EXPECT_TRUE(rb.rule);
  EXPECT_TRUE(std::isinf(rb.window_s));
  EXPECT_EQ(rb.max_distance_m, 1.3);
  EXPECT_EQ(rb.max_speed_difference, 0.2);
  EXPECT_EQ(to_text(rb), rule_text);
  EXPECT_EQ(describe(rb),
            "learned rule: median distance <= 1.3 m and median speed difference <= 0.2 m/s over the whole common "
            "time, min-moving 0.5, linkage single");

  // A model file without the settings lines: all features, min-moving 0.5, single linkage.
  std::string old = to_text(m);
  for (const char* key : {"features", "min_moving", "linkage"}) {
    const size_t at = old.find(std::string("\n") + key);
    old.erase(at, old.find('\n', at + 1) - at);
  }
  const PairModel plain = parse_pair_model(old, "old");
  EXPECT_EQ(plain.features.count(), static_cast<size_t>(kPairFeatureCount));
  EXPECT_EQ(plain.min_moving_fraction, 0.5);
  EXPECT_EQ(plain.linkage, GroupLinkage::kSingle);
}

TEST(PairModel, BuiltinModelForAKnownSceneWasNotTrainedOnIt) {
  ASSERT_EQ(builtin_pair_models().size(), 4u);
  for (const char* scene : {"seq_eth", "seq_hotel", "zara01"}) {
    const PairModel& m = builtin_pair_model_for(scene);
    EXPECT_FALSE(m.trained_on_scene(scene)) << scene;
    EXPECT_EQ(m.trained_on.size(), 2u) << scene;
  }
  EXPECT_EQ(builtin_pair_model_for("my_street").trained_on.size(), 3u);
}

TEST(PairModel, GroupOptionsDefaultsAreTheBuiltinModelsSettings) {
  const PairModel& m = builtin_pair_model_for("");
  const GroupOptions defaults;
  EXPECT_EQ(defaults.window_s, m.window_s);
  EXPECT_EQ(defaults.velocity_span_s, m.velocity_span_s);
  EXPECT_EQ(defaults.min_moving_fraction, m.min_moving_fraction);
  EXPECT_EQ(defaults.linkage, m.linkage);
  const GroupOptions with = options_for(std::make_shared<const PairModel>(m));
  EXPECT_EQ(with.window_s, m.window_s);
  EXPECT_EQ(with.model.get() != nullptr, true);
}

}  // namespace
}  // namespace bodyrec::testing
