#include "bodyrec/reid/resample.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace bodyrec {
namespace {

cv::Mat textured(cv::Size size) {
  cv::Mat image(size, CV_8UC3);
  cv::RNG rng(11);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

double max_difference(const cv::Mat& a, const cv::Mat& b) { return cv::norm(a, b, cv::NORM_INF); }

TEST(Resample, AreaWhenShrinkingBilinearWhenAnySideGrows) {
  const cv::Mat big = textured({100, 250}), small = textured({24, 64}), wide = textured({64, 100});
  cv::Mat area, linear, mixed;
  cv::resize(big, area, {48, 128}, 0, 0, cv::INTER_AREA);
  cv::resize(small, linear, {48, 128}, 0, 0, cv::INTER_LINEAR);
  cv::resize(wide, mixed, {48, 128}, 0, 0, cv::INTER_LINEAR);  // narrower but taller: a side grows
  EXPECT_EQ(max_difference(resample_image(big, {48, 128}), area), 0.0);
  EXPECT_EQ(max_difference(resample_image(small, {48, 128}), linear), 0.0);
  EXPECT_EQ(max_difference(resample_image(wide, {48, 128}), mixed), 0.0);
  // The size it already has: the same pixels, not a copy.
  EXPECT_EQ(resample_image(big, {100, 250}).data, big.data);
}

TEST(Resample, MasksKeepTheirValues) {
  cv::Mat mask = cv::Mat::zeros(64, 24, CV_8U);
  mask(cv::Rect(6, 10, 12, 40)).setTo(255);
  const cv::Mat out = resample_mask(mask, {48, 128});
  ASSERT_EQ(out.size(), cv::Size(48, 128));
  EXPECT_EQ(cv::countNonZero((out != 0) & (out != 255)), 0);
  EXPECT_EQ(cv::countNonZero(out), 4 * 12 * 40);
}

}  // namespace
}  // namespace bodyrec
