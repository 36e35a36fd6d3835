#include "bodyrec/store/scan_quality.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace bodyrec {
namespace {

cv::Mat checker(int rows, int cols) {
  cv::Mat m(rows, cols, CV_8UC3);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) m.at<cv::Vec3b>(y, x) = ((x / 4 + y / 4) % 2) ? cv::Vec3b(255, 255, 255) : cv::Vec3b(0, 0, 0);
  return m;
}

TEST(ScanQuality, SharpBeatsBlurredAndCutOffBodiesAreIncomplete) {
  const cv::Mat sharp = checker(120, 60);
  cv::Mat blurred;
  cv::GaussianBlur(sharp, blurred, cv::Size(9, 9), 3);
  cv::Mat mask = cv::Mat::zeros(120, 60, CV_8UC1);
  mask(cv::Rect(10, 10, 40, 100)).setTo(255);  // 4000 px, inside the frame
  const ScanQuality s = scan_quality(sharp, mask), b = scan_quality(blurred, mask);
  EXPECT_GT(s.sharpness, 0.9);
  EXPECT_LT(b.sharpness, s.sharpness);
  EXPECT_DOUBLE_EQ(s.completeness, 1.0);
  EXPECT_GT(s.score, b.score);

  cv::Mat cut = cv::Mat::zeros(120, 60, CV_8UC1);
  cut(cv::Rect(10, 20, 40, 100)).setTo(255);  // touches the bottom edge
  EXPECT_DOUBLE_EQ(scan_quality(sharp, cut).completeness, 0.75);
  cv::Mat small = cv::Mat::zeros(120, 60, CV_8UC1);
  small(cv::Rect(10, 10, 20, 50)).setTo(255);  // 1000 px
  EXPECT_DOUBLE_EQ(scan_quality(sharp, small).completeness, 0.5);
  EXPECT_EQ(scan_quality(sharp, cv::Mat::zeros(120, 60, CV_8UC1)).score, 0.0);
}

}  // namespace
}  // namespace bodyrec
