#include "bodyrec/reid/gog_features.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

cv::Mat person(cv::Scalar top, cv::Scalar bottom, int seed) {
  cv::Mat image(128, 48, CV_8UC3, cv::Scalar(90, 90, 90));
  cv::rectangle(image, cv::Rect(12, 10, 24, 50), top, cv::FILLED);
  cv::rectangle(image, cv::Rect(14, 60, 20, 60), bottom, cv::FILLED);
  cv::RNG rng(static_cast<uint64_t>(seed));
  cv::Mat noise(image.size(), CV_8UC3);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 12);
  return image + noise;
}

double distance(const std::vector<float>& a, const std::vector<float>& b) {
  double s = 0;
  for (size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return s;
}

// Pixel features of 8 values: patch Gaussians embedded in 9x9 matrices -> 45 values; region Gaussians of
// those in 46x46 -> 1081 values; 7 regions. nRnG has 7 pixel features: 36 -> 703.
TEST(Gog, Lengths) {
  EXPECT_EQ(gog_length(GogColour::kRgb), 7 * 1081);
  EXPECT_EQ(gog_length(GogColour::kLab), 7567);
  EXPECT_EQ(gog_length(GogColour::kHsv), 7567);
  EXPECT_EQ(gog_length(GogColour::kNrNg), 7 * 703);
  const cv::Mat image = person({0, 0, 200}, {200, 0, 0}, 1);
  for (GogColour c : {GogColour::kRgb, GogColour::kLab, GogColour::kHsv, GogColour::kNrNg}) {
    const auto f = gog_features({image, {}}, c);
    ASSERT_EQ(f.size(), size_t(gog_length(c)));
    for (float x : f) ASSERT_TRUE(std::isfinite(x));
  }
}

// A uniform image: every patch has the same Gaussian apart from the vertical position, and the log of the
// embedded matrix of a region is finite and the same for regions of equal content; the scaling by
// |S|^(-1/(d+1)) makes the matrix's determinant 1, so the log's trace (the sum of the diagonal entries of
// the half-vectorisation) is 0 for every region.
TEST(Gog, EmbeddedGaussiansHaveUnitDeterminant) {
  const cv::Mat grey(128, 48, CV_8UC3, cv::Scalar(100, 120, 140));
  const auto f = gog_features({grey, {}}, GogColour::kRgb);
  const int m = 45, n = m + 1, per_region = n * (n + 1) / 2;
  for (int g = 0; g < 7; ++g) {
    double trace = 0;
    int k = g * per_region;
    for (int i = 0; i < n; ++i)
      for (int j = i; j < n; ++j, ++k)
        if (i == j) trace += f[static_cast<size_t>(k)];
    EXPECT_NEAR(trace, 0.0, 1e-3) << "region " << g;
  }
}

TEST(Gog, RegionsAreLocalAndMasksRemoveTheBody) {
  const cv::Mat a = person({0, 0, 200}, {200, 0, 0}, 2);
  cv::Mat b = a.clone();
  b(cv::Rect(0, 96, 48, 32)).setTo(cv::Scalar(0, 200, 0));  // only the last rows differ
  const auto fa = gog_features({a, {}}, GogColour::kHsv), fb = gog_features({b, {}}, GogColour::kHsv);
  const size_t per_region = 1081;
  // Regions 0-3 take the patches centred in rows 0..79 (height 32, step 16), which reach row 81 at most:
  // unchanged. Region 4 reaches row 97.
  EXPECT_EQ(std::vector<float>(fa.begin(), fa.begin() + 4 * per_region),
            std::vector<float>(fb.begin(), fb.begin() + 4 * per_region));
  EXPECT_NE(std::vector<float>(fa.begin() + 4 * per_region, fa.begin() + 5 * per_region),
            std::vector<float>(fb.begin() + 4 * per_region, fb.begin() + 5 * per_region));
  EXPECT_GT(distance(std::vector<float>(fa.begin() + 6 * per_region, fa.end()),
                     std::vector<float>(fb.begin() + 6 * per_region, fb.end())),
            1.0);
  // No body pixel: every region is empty, all zeros.
  const auto none = gog_features({a, cv::Mat::zeros(a.size(), CV_8U)}, GogColour::kRgb);
  EXPECT_TRUE(std::all_of(none.begin(), none.end(), [](float x) { return x == 0.0f; }));
}

TEST(Gog, SameClothesAreCloserThanOtherClothes) {
  for (GogColour c : {GogColour::kRgb, GogColour::kLab, GogColour::kHsv, GogColour::kNrNg}) {
    const auto a = gog_features({person({0, 0, 200}, {200, 0, 0}, 3), {}}, c);
    const auto same = gog_features({person({0, 0, 200}, {200, 0, 0}, 4), {}}, c);
    const auto other = gog_features({person({0, 200, 0}, {0, 200, 200}, 3), {}}, c);
    EXPECT_LT(distance(a, same), distance(a, other)) << static_cast<int>(c);
  }
}

TEST(Gog, OptionsAreChecked) {
  GogOptions bad;
  bad.epsilon = 0;
  EXPECT_THROW(bad.check(), UsageError);
  bad = {};
  bad.regions = 0;
  EXPECT_THROW(bad.check(), UsageError);
  bad = {};
  bad.patch = 1;
  EXPECT_THROW(bad.check(), UsageError);
}

}  // namespace
}  // namespace bodyrec
