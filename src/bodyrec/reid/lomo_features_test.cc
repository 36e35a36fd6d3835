#include "bodyrec/reid/lomo_features.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/resample.h"
#include "bodyrec/reid/retinex.h"

namespace bodyrec {
namespace {

double norm_of(const std::vector<float>& v, size_t begin, size_t end) {
  double s = 0;
  for (size_t i = begin; i < end; ++i) s += double(v[i]) * v[i];
  return std::sqrt(s);
}

cv::Mat person(cv::Scalar top, cv::Scalar bottom, cv::Scalar background) {
  cv::Mat image(128, 48, CV_8UC3, background);
  cv::rectangle(image, cv::Rect(12, 10, 24, 50), top, cv::FILLED);
  cv::rectangle(image, cv::Rect(14, 60, 20, 60), bottom, cv::FILLED);
  cv::RNG rng(7);
  cv::Mat noise(image.size(), CV_8UC3);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 12);
  return image + noise;
}

constexpr size_t kColour = 40 * 512, kTexture = 40 * 81;

// As LOMO.m: three parts (joint HSV, SILTP R=3, SILTP R=5), each of unit norm.
void expect_unit_parts(const std::vector<float>& f) {
  ASSERT_EQ(f.size(), kColour + 2 * kTexture);
  EXPECT_NEAR(norm_of(f, 0, kColour), 1.0, 1e-5);
  EXPECT_NEAR(norm_of(f, kColour, kColour + kTexture), 1.0, 1e-5);
  EXPECT_NEAR(norm_of(f, kColour + kTexture, f.size()), 1.0, 1e-5);
}

TEST(Lomo, LengthAndPerPartUnitNorms) {
  EXPECT_EQ(lomo_length(), 40 * (512 + 162));  // 24 + 11 + 5 patch rows
  EXPECT_EQ(lomo_colour_length(), int(kColour));
  EXPECT_EQ(lomo_texture_length(), int(kTexture));
  const auto f = lomo_features({person({0, 0, 200}, {200, 0, 0}, {90, 90, 90}), {}});
  expect_unit_parts(f);
  for (float x : f) EXPECT_GE(x, 0.0f);
}

// LOMO.m pools the quantised H, S and V indices (floored 2x2 means), not the colours: a checkerboard of
// pure red (bins h 0, s 7, v 7) and cyan (h 4) becomes bin h 2 (green) at the coarser scales, where
// pooled colours would be grey (s 0). Joint bin = (v * 8 + s) * 8 + h.
TEST(Lomo, CoarserScalesPoolTheQuantisedChannelsAsLomoM) {
  cv::Mat board(128, 48, CV_8UC3);
  for (int y = 0; y < board.rows; ++y)
    for (int x = 0; x < board.cols; ++x)
      board.at<cv::Vec3b>(y, x) = (x + y) % 2 ? cv::Vec3b(0, 0, 255) : cv::Vec3b(255, 255, 0);
  LomoOptions seen;
  seen.retinex = false;
  const auto f = lomo_features({board, {}}, seen);
  expect_unit_parts(f);
  const size_t red = 504, cyan = 508, green = 506;
  auto bins_in_row = [&](size_t row) {
    std::vector<size_t> nonzero;
    for (size_t b = 0; b < 512; ++b)
      if (f[row * 512 + b] > 0) nonzero.push_back(b);
    return nonzero;
  };
  EXPECT_EQ(bins_in_row(0), (std::vector<size_t>{red, cyan}));  // full scale: 50 red, 50 cyan per patch
  EXPECT_EQ(bins_in_row(24), std::vector<size_t>{green});       // first row of the second scale
  EXPECT_EQ(bins_in_row(39), std::vector<size_t>{green});       // last row of the third scale
  // log(1 + 50) at full scale, log(1 + 100) at the coarser ones, before the part's normalisation.
  EXPECT_NEAR(f[red] / f[24 * 512 + green], std::log(51.0) / std::log(101.0), 1e-5);
}

TEST(Lomo, DifferentClothesAreFartherThanTheSameClothesOnAnotherBackground) {
  const auto a = lomo_features({person({0, 0, 200}, {200, 0, 0}, {90, 90, 90}), {}});
  const auto same = lomo_features({person({0, 0, 200}, {200, 0, 0}, {60, 100, 80}), {}});
  const auto other = lomo_features({person({0, 200, 0}, {0, 200, 200}, {90, 90, 90}), {}});
  auto dist = [](const std::vector<float>& x, const std::vector<float>& y) {
    double s = 0;
    for (size_t i = 0; i < x.size(); ++i) s += (x[i] - y[i]) * (x[i] - y[i]);
    return s;
  };
  EXPECT_LT(dist(a, same), dist(a, other));
}

TEST(Lomo, MaskRemovesTheBackground) {
  const cv::Mat a = person({0, 0, 200}, {200, 0, 0}, {90, 90, 90});
  const cv::Mat b = person({0, 0, 200}, {200, 0, 0}, {0, 220, 220});
  cv::Mat mask = cv::Mat::zeros(a.size(), CV_8U);
  mask(cv::Rect(12, 10, 24, 50)).setTo(255);
  mask(cv::Rect(14, 60, 20, 60)).setTo(255);
  LomoOptions plain;
  plain.retinex = false;  // Retinex blurs background into the body: compare raw colours
  const auto fa = lomo_features({a, mask}, plain), fb = lomo_features({b, mask}, plain);
  const auto ua = lomo_features({a, {}}, plain), ub = lomo_features({b, {}}, plain);
  expect_unit_parts(fa);
  double masked = 0, unmasked = 0;
  for (size_t i = 0; i < 24 * 512; ++i) {  // colour part, full scale (pooled scales mix edge pixels)
    masked += std::abs(fa[i] - fb[i]);
    unmasked += std::abs(ua[i] - ub[i]);
  }
  // Background pixels are not counted: the full-scale counts are equal, and only the normalisation
  // (shared with the pooled scales, where edge pixels mix body and background) differs a little.
  EXPECT_GT(unmasked, 0.5);
  EXPECT_LT(masked, 0.05 * unmasked);
  // A fully masked image has no body pixels: all zeros.
  const auto none = lomo_features({a, cv::Mat::zeros(a.size(), CV_8U)});
  EXPECT_EQ(std::accumulate(none.begin(), none.end(), 0.0), 0.0);
}

double max_difference(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0;
  for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, double(std::abs(a[i] - b[i])));
  return worst;
}

// The mirror option equals the mean of the image's feature and its flipped image's feature (computed the
// long way), each part scaled back to unit norm, and makes the feature left-right invariant.
TEST(Lomo, MirrorOptionAveragesWithTheMirrorImage) {
  cv::Mat image = person({0, 0, 200}, {200, 0, 0}, {90, 90, 90});
  cv::rectangle(image, cv::Rect(12, 20, 8, 30), cv::Scalar(0, 220, 0), cv::FILLED);  // a bag on one side
  cv::Mat flipped, mask = cv::Mat::zeros(image.size(), CV_8U);
  cv::rectangle(mask, cv::Rect(10, 8, 28, 114), 255, cv::FILLED);
  cv::flip(image, flipped, 1);
  for (bool retinex : {false, true}) {
    LomoOptions one, both;
    one.retinex = both.retinex = retinex;
    both.mirror = true;
    for (const cv::Mat& m : {cv::Mat(), mask}) {
      cv::Mat flipped_mask;
      if (!m.empty()) cv::flip(m, flipped_mask, 1);
      const auto a = lomo_features({image, m}, one), b = lomo_features({flipped, flipped_mask}, one);
      std::vector<float> mean(a.size());
      for (size_t i = 0; i < a.size(); ++i) mean[i] = 0.5f * (a[i] + b[i]);
      const size_t ends[] = {kColour, kColour + kTexture, mean.size()};
      size_t begin = 0;
      for (size_t end : ends) {
        const double norm = norm_of(mean, begin, end);
        for (size_t i = begin; i < end; ++i) mean[i] /= static_cast<float>(norm);
        begin = end;
      }
      const auto mirrored = lomo_features({image, m}, both);
      ASSERT_EQ(mirrored.size(), a.size());
      EXPECT_LT(max_difference(mirrored, mean), 1e-6) << "retinex " << retinex;
      EXPECT_LT(max_difference(mirrored, lomo_features({flipped, flipped_mask}, both)), 1e-6);
      EXPECT_GT(max_difference(a, b), 0.02);  // the bag makes the image and its mirror differ
      expect_unit_parts(mirrored);
      // lomo_parts gives the unmirrored parts of the same call too.
      LomoParts own;
      const LomoParts parts = lomo_parts({image, m}, one, !retinex, retinex, true, &own);
      EXPECT_EQ(own.colour[retinex ? 1 : 0], std::vector<float>(a.begin(), a.begin() + kColour));
      EXPECT_EQ(parts.siltp[1], std::vector<float>(mirrored.begin() + kColour + kTexture, mirrored.end()));
    }
  }
}

TEST(Lomo, AnyCropSizeIsResampledAndOptionsAreChecked) {
  const cv::Mat crop = person({0, 0, 200}, {200, 0, 0}, {90, 90, 90});
  cv::Mat big;
  cv::resize(crop, big, {100, 250});
  EXPECT_EQ(lomo_features({big, {}}).size(), size_t(lomo_length()));
  // Every image is resampled to 48x128 first, as the published recipe does (resample.h).
  EXPECT_EQ(lomo_features({big, {}}), lomo_features({resample_image(big, {48, 128}), {}}));
  LomoOptions bad;
  bad.hsv_bins = 1;
  EXPECT_THROW(bad.check(), UsageError);
}

TEST(Retinex, BrightensADimImageAndKeepsItsHues) {
  cv::Mat dim(64, 32, CV_8UC3);
  cv::randu(dim, cv::Scalar(10, 20, 30), cv::Scalar(20, 40, 60));  // dim, orange-ish (B < G < R)
  const cv::Mat out = multiscale_retinex(dim);
  ASSERT_EQ(out.size(), dim.size());
  EXPECT_GT(cv::mean(out)[2], 3 * cv::mean(dim)[2]);
  cv::Mat hsv_in, hsv_out;
  cv::cvtColor(dim, hsv_in, cv::COLOR_BGR2HSV);
  cv::cvtColor(out, hsv_out, cv::COLOR_BGR2HSV);
  // Hue is kept up to rounding (dark input pixels quantise coarsely): compare the means.
  std::vector<cv::Mat> a, b;
  cv::split(hsv_in, a);
  cv::split(hsv_out, b);
  EXPECT_NEAR(cv::mean(a[0])[0], cv::mean(b[0])[0], 2.0);
}

}  // namespace
}  // namespace bodyrec
