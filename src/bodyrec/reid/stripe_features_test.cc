#include "bodyrec/reid/stripe_features.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/appearance_matcher.h"
#include "bodyrec/reid/xqda.h"

namespace bodyrec {
namespace {

// A 1.80 m person in a 180-row crop (1 cm per row): shirt from 1.55 to 0.85 m, trousers below, with each
// row's height above the floor as an RGB-D scan measures it.
PersonImage dressed(const cv::Scalar& shirt, const cv::Scalar& trousers, const cv::Scalar& background) {
  PersonImage p;
  p.bgr = cv::Mat(180, 64, CV_8UC3, background);
  p.mask = cv::Mat(180, 64, CV_8U, cv::Scalar(0));
  cv::rectangle(p.bgr, cv::Rect(12, 25, 40, 70), shirt, cv::FILLED);
  cv::rectangle(p.bgr, cv::Rect(16, 95, 32, 85), trousers, cv::FILLED);
  cv::rectangle(p.mask, cv::Rect(12, 25, 40, 70), cv::Scalar(255), cv::FILLED);
  cv::rectangle(p.mask, cv::Rect(16, 95, 32, 85), cv::Scalar(255), cv::FILLED);
  for (int y = 0; y < 180; ++y) p.row_height_m.push_back(1.80f - 0.01f * static_cast<float>(y) - 0.005f);
  return p;
}

double band_norm(const std::vector<float>& f, int band) {
  double n = 0;
  for (int i = 0; i < 128; ++i) n += f[static_cast<size_t>(band * 128 + i)] * f[static_cast<size_t>(band * 128 + i)];
  return n;
}

TEST(StripeFeatures, BandsByHeightAboveTheFloor) {
  EXPECT_EQ(stripe_length(), 11 * 8 * 4 * 4);
  const std::vector<float> f = stripe_features(dressed({0, 0, 200}, {200, 0, 0}, {0, 255, 0}));
  ASSERT_EQ(f.size(), 1408u);
  // Body pixels from 0 to 1.55 m: bands 0-7 (0-1.6 m) hold them, each of squared norm 1/2; the bands
  // above 1.6 m (the crop's top rows are background) are empty.
  for (int b = 0; b < 11; ++b) EXPECT_NEAR(band_norm(f, b), b <= 7 ? 0.5 : 0.0, 1e-5) << "band " << b;
}

TEST(StripeFeatures, MaskRemovesTheBackgroundAndClothesDecide) {
  const auto a = stripe_features(dressed({0, 0, 200}, {200, 0, 0}, {0, 255, 0}));
  const auto same_other_background = stripe_features(dressed({0, 0, 200}, {200, 0, 0}, {255, 255, 255}));
  const auto other_clothes = stripe_features(dressed({0, 200, 0}, {0, 200, 200}, {0, 255, 0}));
  EXPECT_NEAR(*stripe_distance(a, same_other_background), 0.0, 1e-9);
  // Every common band differs completely: squared Hellinger 1 each, scaled to 8 bands.
  EXPECT_NEAR(*stripe_distance(a, other_clothes), 8.0, 1e-3);
  auto matcher = make_matcher("stripes");
  EXPECT_EQ(matcher->name(), "stripes");
  EXPECT_EQ(matcher->version(), "stripes2");
  EXPECT_GT(matcher->similarity(a, same_other_background), matcher->threshold());
  EXPECT_LT(matcher->similarity(a, other_clothes), matcher->threshold());
  EXPECT_THROW(make_matcher("stripes", "model.yml"), UsageError);
}

TEST(StripeFeatures, AHalfHiddenBodyIsComparedOnWhatShows) {
  const PersonImage full = dressed({0, 0, 200}, {200, 0, 0}, {0, 255, 0});
  // Someone in front hides everything below 1.0 m: the crop ends there (rows 0-79).
  PersonImage upper;
  upper.bgr = full.bgr.rowRange(0, 80).clone();
  upper.mask = full.mask.rowRange(0, 80).clone();
  upper.row_height_m.assign(full.row_height_m.begin(), full.row_height_m.begin() + 80);
  const auto a = stripe_features(full), b = stripe_features(upper);
  // Bands 5-7 (1.0-1.6 m) are the same shirt in both; the others show in one only. Common: 3 bands,
  // fewer than min_common 4.
  EXPECT_FALSE(stripe_distance(a, b));
  StripeOptions three;
  three.min_common = 3;
  ASSERT_TRUE(stripe_distance(a, b, three));
  EXPECT_NEAR(*stripe_distance(a, b, three), 0.0, 1e-6);
  // Without heights the same crop would be stretched over 0-1.75 m: its shirt lands on the legs' bands.
  PersonImage stretched = upper;
  stretched.row_height_m.clear();
  EXPECT_GT(*stripe_distance(a, stripe_features(stretched), three), 2.5);
  // The matcher: too few common bands is the largest distance.
  EXPECT_DOUBLE_EQ(make_matcher("stripes")->similarity(a, b), -8.0);
}

TEST(StripeFeatures, OptionsAreChecked) {
  StripeOptions o;
  o.bands = 0;
  EXPECT_THROW(o.check(), UsageError);
  o = {};
  o.hue_bins = 0;
  EXPECT_THROW(o.check(), UsageError);
  o = {};
  o.min_common = 12;
  EXPECT_THROW(o.check(), UsageError);
  o = {};
  o.band_m = 0;
  EXPECT_THROW(o.check(), UsageError);
}

}  // namespace
}  // namespace bodyrec
