// The pair model: training on separable data, the text form and its errors, built-in model choice.
#include "bodyrec/groups/pair_model.h"

#include <gtest/gtest.h>

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
  examples.resize(10);  // one class only
  EXPECT_THROW(train_pair_model(examples, 0.01), ProcessingError);
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
  const PairModel back = parse_pair_model(to_text(m), "m");
  EXPECT_EQ(back.trained_on, m.trained_on);
  EXPECT_EQ(back.weights, m.weights);
  EXPECT_EQ(back.scale, m.scale);
  EXPECT_EQ(back.bias, m.bias);
  std::string e = input_error([] { parse_pair_model("hello\n", "f.txt"); });
  EXPECT_TRUE(contains(e, "f.txt:1: not a bodyrec pair model")) << e;
  std::string text = to_text(m);
  text.replace(text.find("bias"), 4, "bais");
  e = input_error([&] { parse_pair_model(text, "f.txt"); });
  EXPECT_TRUE(contains(e, "f.txt:9: bais: unknown key")) << e;
  text = to_text(m);
  text.replace(text.find("window_s 8"), 10, "window_s 8 9");
  e = input_error([&] { parse_pair_model(text, "f.txt"); });
  EXPECT_TRUE(contains(e, "f.txt:3: window_s: expected 1 numbers, got 2")) << e;
  e = input_error([] { read_pair_model("/nonexistent/model.txt"); });
  EXPECT_TRUE(contains(e, "no such file")) << e;
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

}  // namespace
}  // namespace bodyrec::testing
