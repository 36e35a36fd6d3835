// Contour sampling, ordering and mirroring on drawn masks with known outlines.
#include "bodyrec/landmarks/contour.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "synthetic_silhouette.h"

namespace bodyrec {
namespace {

cv::Mat square_mask() {  // pixels x 10..49, y 20..59: outline corners (10,20) (49,20) (49,59) (10,59)
  cv::Mat mask = cv::Mat::zeros(100, 120, CV_8U);
  cv::rectangle(mask, cv::Rect(10, 20, 40, 40), 255, cv::FILLED);
  return mask;
}

ContourOptions options(int n) {
  ContourOptions o;
  o.landmarks = n;
  o.min_height = 10;
  return o;
}

TEST(Contour, SquareCornersStartTopLeftClockwise) {
  const BodyContour c = contour_from_mask(square_mask(), options(4));
  ASSERT_EQ(c.status, ContourStatus::kOk);
  const std::vector<cv::Point2d> expected = {{10, 20}, {49, 20}, {49, 59}, {10, 59}};
  EXPECT_EQ(c.points, expected);
  EXPECT_EQ(c.bounds, cv::Rect(10, 20, 40, 40));
  EXPECT_GT(signed_area2(c.points), 0);  // clockwise on screen
}

TEST(Contour, EquallySpacedByArcLength) {
  // Perimeter 4 * 39 = 156 px; 12 points are 13 px apart along the outline.
  const BodyContour c = contour_from_mask(square_mask(), options(12));
  ASSERT_EQ(c.points.size(), 12u);
  EXPECT_EQ(c.points[1], cv::Point2d(23, 20));
  EXPECT_EQ(c.points[3], cv::Point2d(49, 20));
  EXPECT_EQ(c.points[4], cv::Point2d(49, 33));
  EXPECT_EQ(c.points[7], cv::Point2d(36, 59));
  EXPECT_EQ(c.points[11], cv::Point2d(10, 33));
}

TEST(Contour, TopmostTiesGoLeftAndLargestComponentWins) {
  cv::Mat mask = cv::Mat::zeros(120, 120, CV_8U);
  // A head (rows 10..19, columns 40..49) on a body; a bigger-than-nothing blob elsewhere is ignored.
  cv::rectangle(mask, cv::Rect(40, 10, 10, 10), 255, cv::FILLED);
  cv::rectangle(mask, cv::Rect(30, 20, 30, 60), 255, cv::FILLED);
  cv::rectangle(mask, cv::Rect(90, 2, 8, 8), 255, cv::FILLED);
  const BodyContour c = contour_from_mask(mask, options(30));
  ASSERT_EQ(c.status, ContourStatus::kOk);
  EXPECT_EQ(c.points[0], cv::Point2d(40, 10));
  EXPECT_EQ(c.bounds, cv::Rect(30, 10, 30, 70));
  EXPECT_GT(c.points[1].x, 40);  // moving right along the top of the head first
  EXPECT_GT(signed_area2(c.points), 0);
}

TEST(Contour, AHoleLeavesTheOutlineAndALargerComponentInAnothersHoleWins) {
  // A square with a hole: the outline is the square's, as without the hole.
  cv::Mat holed = square_mask();
  cv::rectangle(holed, cv::Rect(20, 30, 20, 20), 0, cv::FILLED);
  EXPECT_EQ(contour_from_mask(holed, options(12)).points, contour_from_mask(square_mask(), options(12)).points);
  // A one-pixel ring (x 5..64, y 15..74: 236 pixels) around the square (1600 pixels) in its hole: the
  // square is the largest component although the ring encloses it.
  cv::Mat ringed = square_mask();
  cv::rectangle(ringed, cv::Rect(5, 15, 60, 60), 255, 1);
  const BodyContour c = contour_from_mask(ringed, options(4));
  ASSERT_EQ(c.status, ContourStatus::kOk);
  EXPECT_EQ(c.bounds, cv::Rect(10, 20, 40, 40));
  EXPECT_EQ(c.points, contour_from_mask(square_mask(), options(4)).points);
}

TEST(Contour, SkipsSmallBorderAndEmpty) {
  ContourOptions o = options(10);
  o.min_height = 41;
  EXPECT_EQ(contour_from_mask(square_mask(), o).status, ContourStatus::kTooSmall);
  o.min_height = 40;
  EXPECT_EQ(contour_from_mask(square_mask(), o).status, ContourStatus::kOk);

  cv::Mat border = cv::Mat::zeros(100, 100, CV_8U);
  cv::rectangle(border, cv::Rect(0, 10, 40, 40), 255, cv::FILLED);  // left column: 40 of 156 outline pixels on the border
  const BodyContour c = contour_from_mask(border, options(10));
  EXPECT_EQ(c.status, ContourStatus::kTouchesBorder);
  EXPECT_NEAR(c.border_fraction, 40.0 / 156.0, 1e-9);
  o = options(10);
  o.max_border_fraction = 0.3;
  EXPECT_EQ(contour_from_mask(border, o).status, ContourStatus::kOk);

  EXPECT_EQ(contour_from_mask(cv::Mat::zeros(50, 50, CV_8U), options(10)).status, ContourStatus::kEmpty);
  EXPECT_THROW(options(2).check(), UsageError);
}

TEST(Contour, MirrorKeepsHeadTopAndClockwiseAndTwiceIsIdentity) {
  const BodyContour c = contour_from_mask(square_mask(), options(4));
  const auto m = mirror_contour(c.points, 120);
  const std::vector<cv::Point2d> expected = {{109, 20}, {109, 59}, {70, 59}, {70, 20}};
  EXPECT_EQ(m, expected);
  EXPECT_GT(signed_area2(m), 0);
  EXPECT_EQ(mirror_contour(m, 120), c.points);

  const auto person = testing::make_silhouette(cv::Size(160, 220), 180, 7);
  const BodyContour body = contour_from_mask(person.mask, options(180));
  ASSERT_EQ(body.status, ContourStatus::kOk);
  const auto mirrored = mirror_contour(body.points, 160);
  EXPECT_EQ(mirrored[0], cv::Point2d(159 - body.points[0].x, body.points[0].y));
  EXPECT_GT(signed_area2(mirrored), 0);
  const auto twice = mirror_contour(mirrored, 160);
  ASSERT_EQ(twice.size(), body.points.size());
  for (size_t i = 0; i < twice.size(); ++i) EXPECT_LT(cv::norm(twice[i] - body.points[i]), 1e-9) << i;
}

TEST(Contour, SilhouetteSamplingIsEvenAndOnTheOutline) {
  const auto person = testing::make_silhouette(cv::Size(160, 220), 180, 3);
  const BodyContour c = contour_from_mask(person.mask, options(180));
  ASSERT_EQ(c.status, ContourStatus::kOk);
  EXPECT_NEAR(c.bounds.height, 180, 2);
  EXPECT_EQ(c.points[0].y, c.bounds.y);  // the head top
  for (const auto& p : c.points) {
    // Every landmark lies on the outline: a person pixel (or between two) with background next to it.
    const cv::Point q(cvRound(p.x), cvRound(p.y));
    EXPECT_TRUE(person.mask.at<uchar>(q) != 0 || person.mask.at<uchar>(cv::Point(cvFloor(p.x), cvFloor(p.y))) != 0);
  }
  double min_step = 1e9, max_step = 0;
  for (size_t i = 0; i < c.points.size(); ++i) {
    const double step = cv::norm(c.points[(i + 1) % c.points.size()] - c.points[i]);
    min_step = std::min(min_step, step);
    max_step = std::max(max_step, step);
  }
  EXPECT_LE(max_step, 1.5 * (min_step + 1.0));  // chords of equal arcs: nearly equal
}

TEST(Contour, ResampleAndDistances) {
  const std::vector<cv::Point2d> square = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const auto r = resample_closed(square, 8);
  EXPECT_EQ(r[1], cv::Point2d(5, 0));
  EXPECT_EQ(r[5], cv::Point2d(5, 10));
  EXPECT_DOUBLE_EQ(distance_to_closed_polyline({5, 3}, square), 3.0);
  EXPECT_DOUBLE_EQ(distance_to_closed_polyline({-3, -4}, square), 5.0);
  EXPECT_DOUBLE_EQ(distance_to_closed_polyline({2, 5}, square), 2.0);  // closing segment (0,10)->(0,0)
  EXPECT_DOUBLE_EQ(signed_area2(square), 200.0);
}

TEST(Contour, PointsAtArcAndProjections) {
  const std::vector<cv::Point2d> square = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};  // length 40
  const auto p = points_at_arc(square, {0.0, 0.125, 0.5, 0.9, -0.1, 1.25});
  ASSERT_EQ(p.size(), 6u);
  EXPECT_EQ(p[0], cv::Point2d(0, 0));
  EXPECT_EQ(p[1], cv::Point2d(5, 0));
  EXPECT_EQ(p[2], cv::Point2d(10, 10));
  EXPECT_NEAR(p[3].x, 0, 1e-12);
  EXPECT_NEAR(p[3].y, 4, 1e-12);  // 36 of 40: on the closing side, 4 above the start
  EXPECT_NEAR(cv::norm(p[4] - p[3]), 0, 1e-12);  // -0.1 is 0.9
  EXPECT_EQ(p[5], cv::Point2d(10, 0));  // 1.25 is 0.25
  EXPECT_TRUE(points_at_arc({}, {0.5}).empty());
  const PolylineProjection a = project_to_closed_polyline({5, 3}, square);
  EXPECT_DOUBLE_EQ(a.distance, 3.0);
  EXPECT_DOUBLE_EQ(a.arc, 0.125);
  const PolylineProjection b = project_to_closed_polyline({-2, 6}, square);  // beside the closing side
  EXPECT_DOUBLE_EQ(b.distance, 2.0);
  EXPECT_DOUBLE_EQ(b.arc, 0.85);
  // A repeated vertex (a zero-length segment) and fractions out of order give the same points.
  const std::vector<cv::Point2d> repeated = {{0, 0}, {10, 0}, {10, 0}, {10, 10}, {0, 10}};
  const std::vector<cv::Point2d> q = points_at_arc(repeated, {0.3, 0.25, 0.1, 0.9, 0.5});
  const std::vector<cv::Point2d> expected = {{10, 2}, {10, 0}, {4, 0}, p[3], {10, 10}};
  ASSERT_EQ(q.size(), expected.size());
  for (size_t i = 0; i < q.size(); ++i) EXPECT_NEAR(cv::norm(q[i] - expected[i]), 0, 1e-12) << i;
  // resample_closed is points_at_arc at k / n.
  EXPECT_EQ(resample_closed(square, 8), points_at_arc(square, {0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875}));
}

}  // namespace
}  // namespace bodyrec
