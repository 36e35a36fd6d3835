#include "bodyrec/reid/stripe_features.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/appearance_matcher.h"
#include "bodyrec/reid/xqda.h"

namespace bodyrec {
namespace {

PersonImage dressed(const cv::Scalar& shirt, const cv::Scalar& trousers, const cv::Scalar& background) {
  PersonImage p;
  p.bgr = cv::Mat(192, 64, CV_8UC3, background);
  p.mask = cv::Mat(192, 64, CV_8U, cv::Scalar(0));
  cv::rectangle(p.bgr, cv::Rect(12, 24, 40, 72), shirt, cv::FILLED);
  cv::rectangle(p.bgr, cv::Rect(16, 96, 32, 90), trousers, cv::FILLED);
  cv::rectangle(p.mask, cv::Rect(12, 24, 40, 72), cv::Scalar(255), cv::FILLED);
  cv::rectangle(p.mask, cv::Rect(16, 96, 32, 90), cv::Scalar(255), cv::FILLED);
  return p;
}

TEST(StripeFeatures, LengthAndHellingerNorms) {
  EXPECT_EQ(stripe_length(), 8 * 8 * 4 * 4);
  const std::vector<float> f = stripe_features(dressed({0, 0, 200}, {200, 0, 0}, {0, 255, 0}));
  ASSERT_EQ(f.size(), 1024u);
  // Each stripe with body pixels has squared norm 1/2 (sqrt of a distribution, halved); the top stripe
  // (rows 0-23) has none.
  for (int s = 0; s < 8; ++s) {
    double n = 0;
    for (int i = 0; i < 128; ++i) n += f[static_cast<size_t>(s * 128 + i)] * f[static_cast<size_t>(s * 128 + i)];
    EXPECT_NEAR(n, s == 0 ? 0.0 : 0.5, 1e-5) << "stripe " << s;
  }
}

TEST(StripeFeatures, MaskRemovesTheBackgroundAndClothesDecide) {
  const auto a = stripe_features(dressed({0, 0, 200}, {200, 0, 0}, {0, 255, 0}));
  const auto same_other_background = stripe_features(dressed({0, 0, 200}, {200, 0, 0}, {255, 255, 255}));
  const auto other_clothes = stripe_features(dressed({0, 200, 0}, {0, 200, 200}, {0, 255, 0}));
  EXPECT_NEAR(squared_distance(a, same_other_background), 0.0, 1e-9);
  // Every body stripe differs completely: 7 stripes x squared Hellinger 1.
  EXPECT_NEAR(squared_distance(a, other_clothes), 7.0, 1e-4);
  auto matcher = make_matcher("stripes");
  EXPECT_EQ(matcher->name(), "stripes");
  EXPECT_GT(matcher->similarity(a, same_other_background), matcher->threshold());
  EXPECT_LT(matcher->similarity(a, other_clothes), matcher->threshold());
  EXPECT_THROW(make_matcher("stripes", "model.yml"), UsageError);
}

TEST(StripeFeatures, OptionsAreChecked) {
  StripeOptions o;
  o.stripes = 0;
  EXPECT_THROW(o.check(), UsageError);
  o = {};
  o.hue_bins = 0;
  EXPECT_THROW(o.check(), UsageError);
}

}  // namespace
}  // namespace bodyrec
