// CCD kernel, outline tracing and contour landmarks on label images with known shapes.
#include "bodyrec/rgbd/contour.h"

#include <set>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"
#include "bodyrec/rgbd/recording.h"

#include "test_support.h"

namespace bodyrec {
namespace {

cv::Mat square_labels() {  // a 5x5 body (label 2) at (1,1)..(5,5) in a 7x7 image
  cv::Mat l(7, 7, CV_8U, cv::Scalar(kNoBody));
  l(cv::Rect(1, 1, 5, 5)).setTo(2);
  return l;
}

TEST(CcdContour, CrossTestMarksTheRingOfABody) {
  cv::Mat c;
  ccd_contour(square_labels(), c);
  EXPECT_EQ(cv::countNonZero(c == 2), 16);  // the 5x5 square's border ring
  EXPECT_EQ(c.at<uint8_t>(1, 1), 2);
  EXPECT_EQ(c.at<uint8_t>(3, 3), kNoBody);  // interior: all 4 neighbours are the body
  // Two touching bodies each get their own edge; the image border is never a contour pixel.
  cv::Mat two(4, 6, CV_8U, cv::Scalar(0));
  two(cv::Rect(3, 0, 3, 4)).setTo(1);
  ccd_contour(two, c);
  EXPECT_EQ(c.at<uint8_t>(1, 2), 0);
  EXPECT_EQ(c.at<uint8_t>(1, 3), 1);
  EXPECT_EQ(c.at<uint8_t>(1, 1), kNoBody);
  EXPECT_EQ(c.at<uint8_t>(0, 2), kNoBody);
}

TEST(Outline, TracedAndOpenCvAgreeAndRunClockwiseFromTheTop) {
  const auto traced = trace_outline(square_labels(), 2);
  ASSERT_EQ(traced.size(), 16u);
  EXPECT_EQ(traced[0], cv::Point(1, 1));
  EXPECT_EQ(traced[1], cv::Point(2, 1));  // clockwise on the image: along the top to the right
  EXPECT_EQ(traced[4], cv::Point(5, 1));
  EXPECT_EQ(traced[8], cv::Point(5, 5));
  const auto cv_outline = opencv_outline(square_labels(), 2);
  std::set<std::pair<int, int>> a, b;
  for (const auto& p : traced) a.insert({p.x, p.y});
  for (const auto& p : cv_outline) b.insert({p.x, p.y});
  EXPECT_EQ(b.size(), 16u);
  EXPECT_EQ(a, b);
  EXPECT_TRUE(trace_outline(square_labels(), 0).empty());
  // A one-pixel body and an L shape with a thin part still close.
  cv::Mat one(3, 3, CV_8U, cv::Scalar(kNoBody));
  one.at<uint8_t>(1, 1) = 0;
  EXPECT_EQ(trace_outline(one, 0).size(), 1u);
  cv::Mat l(6, 6, CV_8U, cv::Scalar(kNoBody));
  l(cv::Rect(1, 1, 1, 4)).setTo(0);
  l(cv::Rect(1, 4, 4, 1)).setTo(0);
  const auto lo = trace_outline(l, 0);
  // Thin parts are walked out and back; the inner corner (1,4) is cut diagonally on the way back.
  EXPECT_EQ(lo.size(), 11u);
  EXPECT_EQ(lo[0], cv::Point(1, 1));
}

TEST(Landmarks, EqualArcLengthFromTheTopClockwise) {
  // Outline of a 5x5 square (0,0)..(4,4): perimeter 16; top run y = 0, middle at x = 2.
  std::vector<cv::Point> sq;
  for (int x = 0; x < 4; ++x) sq.emplace_back(x, 0);
  for (int y = 0; y < 4; ++y) sq.emplace_back(4, y);
  for (int x = 4; x > 0; --x) sq.emplace_back(x, 4);
  for (int y = 4; y > 0; --y) sq.emplace_back(0, y);
  std::vector<cv::Point> ccw(sq.rbegin(), sq.rend());
  for (const auto& outline : {sq, ccw}) {
    const auto lm = contour_landmarks(outline, 4);
    ASSERT_EQ(lm.size(), 4u);
    EXPECT_EQ(lm[0], cv::Point2d(2, 0));
    EXPECT_EQ(lm[1], cv::Point2d(4, 2));
    EXPECT_EQ(lm[2], cv::Point2d(2, 4));
    EXPECT_EQ(lm[3], cv::Point2d(0, 2));
  }
  const auto eight = contour_landmarks(sq, 8);
  EXPECT_EQ(eight[1], cv::Point2d(4, 0));
  EXPECT_TRUE(contour_landmarks({}, 5).empty());
}

TEST(BodyContours, LandmarksGetCameraSpacePoints) {
  const Intrinsics k = kinect2_depth_intrinsics();
  cv::Mat labels(k.height, k.width, CV_8U, cv::Scalar(kNoBody));
  labels(cv::Rect(200, 100, 60, 200)).setTo(1);
  cv::Mat depth(k.height, k.width, CV_16U, cv::Scalar(4000));
  depth(cv::Rect(200, 100, 60, 200)).setTo(2000);
  depth.at<uint16_t>(100, 230) = 0;  // a hole at the landmark 0 pixel: the nearest valid pixel is used
  for (ContourMethod m : {ContourMethod::kCcd, ContourMethod::kOpenCv}) {
    const auto bodies = body_contours(labels, depth, k, 0.001, 10, m);
    ASSERT_EQ(bodies.size(), 1u);
    EXPECT_EQ(bodies[0].label, 1);
    EXPECT_EQ(bodies[0].outline.size(), 2u * (59 + 199));
    ASSERT_EQ(bodies[0].landmarks.size(), 10u);
    EXPECT_NEAR(bodies[0].landmarks[0].x, 229.5, 0.6);
    EXPECT_EQ(bodies[0].landmarks[0].y, 100);
    ASSERT_TRUE(bodies[0].points[0].has_value());
    EXPECT_NEAR((*bodies[0].points[0])[2], 2.0, 1e-9);
    EXPECT_NEAR((*bodies[0].points[0])[1], (k.cy - 100) / k.fy * 2.0, 1e-9);
    EXPECT_GT(bodies[0].landmarks[1].x, bodies[0].landmarks[0].x);  // clockwise: to the right first
  }
}

TEST(BodyContours, BrokenInput) {
  const Intrinsics k = kinect2_depth_intrinsics();
  const cv::Mat depth(k.height, k.width, CV_16U, cv::Scalar(0));
  EXPECT_TRUE(testing::contains(
      testing::input_error([&] { body_contours(cv::Mat(k.height, k.width, CV_16U), depth, k, 0.001, 5, ContourMethod::kCcd); }),
      "labels must be 8-bit"));
  EXPECT_TRUE(testing::contains(
      testing::input_error([&] { body_contours(cv::Mat(k.height, k.width, CV_8U), cv::Mat(), k, 0.001, 5, ContourMethod::kCcd); }),
      "depth must be 16-bit"));
  EXPECT_THROW(parse_contour_method("snake"), UsageError);
  EXPECT_EQ(parse_contour_method("opencv"), ContourMethod::kOpenCv);
}

}  // namespace
}  // namespace bodyrec
