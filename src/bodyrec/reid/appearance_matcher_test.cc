#include "bodyrec/reid/appearance_matcher.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
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

TEST(LomoMatcher, FeaturesAreTheSameForAnImageAndItsMirror) {
  const auto matcher = make_matcher("lomo");
  EXPECT_EQ(matcher->version(), "lomo3");  // lomo2 features were not mirror-averaged
  const cv::Mat image = person(1, 0);
  cv::Mat mirrored;
  cv::flip(image, mirrored, 1);
  const auto f = matcher->features({image, {}});
  ASSERT_EQ(f.size(), size_t(2 * lomo_length()));
  EXPECT_LT(max_difference(f, matcher->features({mirrored, {}})), 1e-6);
  // ...and not the single-image LOMO (plain colours half).
  LomoOptions plain;
  plain.retinex = false;
  const auto single = lomo_features({image, {}}, plain);
  EXPECT_GT(max_difference(std::vector<float>(f.begin(), f.begin() + lomo_length()), single), 0.01);  // 0.018
}

// A hand-made model of LOMO x 2 input length, tagged with `features`.
XqdaEnsemble model_of(const std::string& features) {
  XqdaEnsemble e;
  cv::RNG rng(5);
  for (int k = 0; k < 2; ++k) {
    XqdaModel m;
    m.projection = cv::Mat(lomo_length(), 3, CV_32F);
    rng.fill(m.projection, cv::RNG::NORMAL, 0, 0.01);
    m.threshold = 1.0;
    m.prepare();
    e.parts.push_back(m);
  }
  e.threshold = 2.0;
  e.id = "deadbeef";
  e.features = features;
  return e;
}

TEST(LomoMatcher, ModelsTrainedOnOtherFeaturesAreRefused) {
  testing::TempDir dir;
  const std::string old_path = (dir / "old.yml").string(), path = (dir / "reid.yml").string();
  model_of("lomo2").save(old_path);
  const std::string error = testing::input_error([&] { make_matcher("default", old_path); });
  EXPECT_TRUE(testing::contains(error, "old.yml")) << error;
  EXPECT_TRUE(testing::contains(error, "'lomo2'")) << error;
  EXPECT_TRUE(testing::contains(error, "train-reid")) << error;
  model_of("lomo3").save(path);
  const auto matcher = make_matcher("default", path);
  EXPECT_EQ(matcher->version(), "lomo3-xqda-deadbeef");
  EXPECT_EQ(matcher->describe({person(2, 1), {}}).size(), 6u);
  EXPECT_DOUBLE_EQ(matcher->threshold(), -2.0);
}

TEST(LomoMatcher, TrainedModelSavesItsFeatureFormat) {
  std::vector<std::vector<float>> features;
  std::vector<TrainingSample> samples;
  auto matcher = make_matcher("default");
  for (int id = 0; id < 6; ++id)
    for (int cam = 0; cam < 2; ++cam) features.push_back(matcher->features({person(id, cam), {}}));
  for (size_t i = 0; i < features.size(); ++i)
    samples.push_back({&features[i], static_cast<int>(i / 2), static_cast<int>(i % 2)});
  matcher->train(samples);
  testing::TempDir dir;
  const std::string path = (dir / "reid.yml").string();
  matcher->save_model(path);
  EXPECT_EQ(XqdaEnsemble::load(path).features, "lomo3");
  const auto back = make_matcher("default", path);
  EXPECT_EQ(back->version(), matcher->version());
  EXPECT_EQ(back->describe({person(3, 1), {}}), matcher->descriptor(features[7]));
}

}  // namespace
}  // namespace bodyrec
