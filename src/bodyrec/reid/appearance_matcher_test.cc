#include "bodyrec/reid/appearance_matcher.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/learned_matcher.h"
#include "bodyrec/reid/lomo_features.h"
#include "test_support.h"

namespace bodyrec {
namespace {

// A person in the identity's colours with a bag on the left, so the image and its mirror differ.
cv::Mat person(int id, int cam) {
  cv::RNG colours(static_cast<uint64_t>(100 + id));
  cv::Mat image(128, 48, CV_8UC3, cv::Scalar(120, 130, 125));
  const cv::Scalar shirt(colours.uniform(0, 256), colours.uniform(0, 256), colours.uniform(0, 256));
  const cv::Scalar trousers(colours.uniform(0, 256), colours.uniform(0, 256), colours.uniform(0, 256));
  cv::rectangle(image, cv::Rect(10, 12, 26, 50), shirt, cv::FILLED);
  cv::rectangle(image, cv::Rect(13, 62, 20, 58), trousers, cv::FILLED);
  cv::rectangle(image, cv::Rect(4, 30, 8, 24), cv::Scalar(30, 60, 200), cv::FILLED);
  cv::Mat noise(image.size(), CV_8UC3);
  cv::RNG rng(static_cast<uint64_t>(id * 2 + cam));
  rng.fill(noise, cv::RNG::UNIFORM, 0, 20);
  return image + noise;
}

double max_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, double(std::abs(a[i] - b[i])));
  return worst;
}

TEST(LomoMatcher, UnlearnedFeaturesAreTheSameForAnImageAndItsMirror) {
  const auto matcher = make_matcher("lomo");
  EXPECT_EQ(matcher->version(), "lomo4m");  // lomo3 had two colour halves, two parts each
  EXPECT_FALSE(matcher->learns());
  const cv::Mat image = person(1, 0);
  cv::Mat mirrored;
  cv::flip(image, mirrored, 1);
  const auto f = matcher->features({image, {}});
  ASSERT_EQ(f.size(), size_t(lomo_length()));
  EXPECT_LT(max_difference(f, matcher->features({mirrored, {}})), 1e-6);
  // ...and not the published LOMO of the image alone.
  EXPECT_GT(max_difference(f, lomo_features({image, {}})), 0.01);
  EXPECT_EQ(matcher->descriptor(f), f);
}

// Features and labels of `people` generated identities in two cameras, as `matcher` computes them.
struct People {
  std::vector<std::vector<float>> features;
  std::vector<TrainingSample> samples;
};
People people_for(const AppearanceMatcher& matcher, int people) {
  People p;
  for (int id = 0; id < people; ++id)
    for (int cam = 0; cam < 2; ++cam) p.features.push_back(matcher.features({person(id, cam), {}}));
  for (size_t i = 0; i < p.features.size(); ++i)
    p.samples.push_back({&p.features[i], static_cast<int>(i / 2), static_cast<int>(i % 2)});
  return p;
}

TEST(LomoMatcher, PublishedRecipeTrainsSavesAndLoads) {
  auto matcher = make_untrained_matcher("lomo-xqda");
  EXPECT_TRUE(matcher->learns());
  const People p = people_for(*matcher, 6);
  ASSERT_EQ(p.features[0], lomo_features({person(0, 0), {}}));  // the published LOMO, nothing more
  EXPECT_THROW(matcher->descriptor(p.features[0]), ProcessingError);  // not trained yet
  matcher->train(p.samples);
  testing::TempDir dir;
  const std::string path = (dir / "published.yml").string();
  matcher->save_model(path);
  const XqdaEnsemble saved = XqdaEnsemble::load(path);
  EXPECT_EQ(saved.features, "lomo4");
  EXPECT_EQ(saved.parts.size(), 1u);
  const auto back = make_matcher("lomo-xqda", path);
  EXPECT_EQ(back->version(), matcher->version());
  EXPECT_EQ(back->describe({person(3, 1), {}}), matcher->descriptor(p.features[7]));
  // Online use needs a model: there is none shipped for the published recipe.
  EXPECT_THROW(make_matcher("lomo-xqda"), UsageError);
  // A published model is not a default model, nor the other way round.
  EXPECT_TRUE(testing::contains(testing::input_error([&] { make_matcher("default", path); }), "'lomo4'"));
}

// A hand-made default model of the given format and variant with one part of `inputs` values.
XqdaEnsemble model_of(const std::string& features, const std::string& variant, int inputs) {
  XqdaEnsemble e;
  XqdaModel m;
  m.projection = cv::Mat(inputs, 3, CV_32F, cv::Scalar(0.01f));
  m.threshold = 1.0;
  m.prepare();
  e.parts.push_back(m);
  e.threshold = 2.0;
  e.id = "deadbeef";
  e.features = features;
  e.variant = variant;
  return e;
}

TEST(LomoMatcher, ModelsTrainedOnOtherFeaturesOrVariantsAreRefused) {
  testing::TempDir dir;
  const std::string old_path = (dir / "old.yml").string(), path = (dir / "reid.yml").string();
  model_of("lomo3", "lomo", lomo_length()).save(old_path);
  const std::string error = testing::input_error([&] { make_matcher("default", old_path); });
  EXPECT_TRUE(testing::contains(error, "old.yml")) << error;
  EXPECT_TRUE(testing::contains(error, "'lomo3'")) << error;
  EXPECT_TRUE(testing::contains(error, "train-reid")) << error;
  // Models of the unsketched features (lomo4-gog1) are default-full's, refused by default and the other way
  // round; default-full reads LOMO's 26960 values as they are.
  model_of("lomo4-gog1", "lomo", lomo_length()).save(path);
  EXPECT_TRUE(testing::contains(testing::input_error([&] { make_matcher("default", path); }), "'lomo4-gog1'"));
  const auto full = make_matcher("default-full", path);
  EXPECT_EQ(full->version(), "lomo4-gog1-xqda-deadbeef");
  EXPECT_EQ(full->describe({person(2, 1), {}}).size(), 3u);
  model_of("lomo4-gog1", "lomo", 8987).save(path);
  EXPECT_TRUE(testing::contains(testing::input_error([&] { make_matcher("default-full", path); }), "26960"));
  EXPECT_THROW(make_matcher("default-full"), UsageError);  // nothing shipped: a model is needed
  model_of("lomo4-gog1-cs3", "sift", 8988).save(path);
  EXPECT_TRUE(testing::contains(testing::input_error([&] { make_matcher("default", path); }), "'variant' 'sift'"));
  // Variant lomo reads LOMO's 26960 values sketched to a third, block by block: 6827 + 1080 + 1080.
  model_of("lomo4-gog1-cs3", "lomo", 100).save(path);
  EXPECT_TRUE(testing::contains(testing::input_error([&] { make_matcher("default", path); }), "8987"));
  model_of("lomo4-gog1-cs3", "lomo", 8987).save(path);
  const auto matcher = make_matcher("default", path);
  EXPECT_EQ(matcher->version(), "lomo4-gog1-cs3-xqda-deadbeef");
  EXPECT_EQ(matcher->describe({person(2, 1), {}}).size(), 3u);
  EXPECT_DOUBLE_EQ(matcher->threshold(), -2.0);
  EXPECT_TRUE(testing::contains(testing::input_error([&] { make_matcher("default-full", path); }), "'lomo4-gog1-cs3'"));
}

// default-full trains the same variants on the unsketched blocks: its parts read each block whole.
TEST(LomoMatcher, DefaultFullTrainsOnTheUnsketchedFeatures) {
  auto matcher = make_untrained_matcher("default-full");
  EXPECT_EQ(matcher->name(), "default-full");
  const People p = people_for(*matcher, 8);
  ASSERT_EQ(p.features[0], make_untrained_matcher("default")->features({person(0, 0), {}}));  // same features
  matcher->train(p.samples);
  EXPECT_TRUE(testing::contains(matcher->summary(), "on the full features")) << matcher->summary();
  testing::TempDir dir;
  const std::string path = (dir / "full.yml.gz").string();
  matcher->save_model(path);
  const XqdaEnsemble saved = XqdaEnsemble::load(path);
  EXPECT_EQ(saved.features, "lomo4-gog1");
  int inputs = 0;
  for (const auto& part : saved.parts) inputs += part.input_length();
  // Every part reads whole blocks (LOMO's 26960 values, GOG's 3 x 7567 + 4921), never a sketched third.
  const std::map<std::string, int> whole = {{"lomo", 26960},
                                            {"lomo-mirror-2c", 2 * 26960},
                                            {"gog", 27622},
                                            {"lomo-mirror-2c+gog", 2 * 26960 + 27622}};
  ASSERT_TRUE(whole.count(saved.variant)) << saved.variant;
  EXPECT_EQ(inputs, whole.at(saved.variant));
  const auto back = make_matcher("default-full", path);
  EXPECT_EQ(back->version(), matcher->version());
  EXPECT_EQ(back->describe({person(5, 1), {}}), matcher->descriptor(p.features[11]));
}

// The default matcher picks its variant on the training people, saves it, and the saved model is found
// without a flag as the shipped model (BODYREC_MODELS first).
TEST(LomoMatcher, DefaultChoosesAVariantAndIsFoundWithoutAFlag) {
  auto matcher = make_untrained_matcher("default");
  const People p = people_for(*matcher, 8);
  matcher->train(p.samples);
  EXPECT_TRUE(testing::contains(matcher->summary(), "chosen by 4-fold cross-validation")) << matcher->summary();
  testing::TempDir dir;
  const std::string path = (dir / kShippedReidModel).string();
  matcher->save_model(path);
  const XqdaEnsemble saved = XqdaEnsemble::load(path);
  EXPECT_EQ(saved.features, "lomo4-gog1-cs3");
  bool known = false;
  for (const auto& v : default_reid_variants()) known |= v.name == saved.variant;
  EXPECT_TRUE(known) << saved.variant;
  setenv("BODYREC_MODELS", dir.path().c_str(), 1);
  const auto shipped = make_matcher("default");
  unsetenv("BODYREC_MODELS");
  EXPECT_EQ(shipped->version(), matcher->version());
  EXPECT_EQ(shipped->describe({person(5, 1), {}}), matcher->descriptor(p.features[11]));
  // Few people: with 3 in both cameras there are no two-person folds, the published variant is trained.
  auto few = make_untrained_matcher("default");
  const People q = people_for(*few, 3);
  few->train(q.samples);
  EXPECT_TRUE(testing::contains(few->summary(), "variant lomo ")) << few->summary();
}

}  // namespace
}  // namespace bodyrec
