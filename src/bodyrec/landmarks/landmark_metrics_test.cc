#include "bodyrec/landmarks/landmark_metrics.h"

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

TEST(LandmarkMetrics, PersonErrorPointToPointAndToContour) {
  const std::vector<cv::Point2d> truth = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  // Every point shifted 2 px right along/over the outline: point-to-point 2; to contour 0, 0, 2, 0.
  const std::vector<cv::Point2d> predicted = {{2, 0}, {12, 0}, {12, 10}, {2, 10}};
  const PersonLandmarkError e = person_landmark_error(predicted, truth, Box(0, 0, 10, 20), 640);
  EXPECT_DOUBLE_EQ(e.mean_px, 2.0);
  EXPECT_DOUBLE_EQ(e.contour_px, 1.0);  // (0 + 2 + 2 + 0) / 4
  EXPECT_DOUBLE_EQ(e.box_height, 20.0);
  EXPECT_DOUBLE_EQ(e.image_width, 640.0);
}

TEST(LandmarkMetrics, SummaryMeanMedianP90) {
  std::vector<PersonLandmarkError> errors;
  for (int i = 1; i <= 11; ++i) errors.push_back({static_cast<double>(i), 1.0, 100.0, 200.0});
  const LandmarkScores s = summarize_landmark_errors(errors);
  EXPECT_EQ(s.persons, 11);
  EXPECT_DOUBLE_EQ(s.mean_px, 6.0);
  EXPECT_DOUBLE_EQ(s.median_px, 6.0);
  EXPECT_DOUBLE_EQ(s.p90_px, 10.0);
  EXPECT_DOUBLE_EQ(s.mean_rel_height, 0.06);
  EXPECT_DOUBLE_EQ(s.p90_rel_height, 0.10);
  EXPECT_DOUBLE_EQ(s.mean_rel_width, 0.03);
  EXPECT_DOUBLE_EQ(s.contour_px, 1.0);
  EXPECT_DOUBLE_EQ(quantile({4, 1, 3, 2}, 0.5), 2.5);
  EXPECT_EQ(summarize_landmark_errors({}).persons, 0);
}

}  // namespace
}  // namespace bodyrec
