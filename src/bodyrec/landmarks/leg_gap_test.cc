#include "bodyrec/landmarks/leg_gap.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/landmarks/contour.h"

namespace bodyrec {
namespace {

// A 24x72 "person": body columns 4..19 on every row, logits 5 on the body and -5 off it.
struct Person {
  cv::Mat mask = cv::Mat::zeros(72, 24, CV_8UC1);
  cv::Mat logits = cv::Mat(72, 24, CV_32FC1, cv::Scalar(-5.0f));
  Person() {
    mask(cv::Rect(4, 0, 16, 72)).setTo(255);
    logits(cv::Rect(4, 0, 16, 72)).setTo(5.0f);
  }
};

// 8-connected body components in rows [top, rows).
int components_below(const cv::Mat& mask, int top) {
  cv::Mat labels;
  return cv::connectedComponents(mask.rowRange(top, mask.rows), labels, 8) - 1;
}

TEST(LegGap, CutsASlitUpTheValleyAsFarAsItStaysBelowTheSlitLogit) {
  Person p;
  // Legs together: the logits dip to 0.7 (above the threshold 0, so the mask is solid) in column 11
  // from row 45 down, and to 1.5 in rows 40..44 (not below the slit logit 1).
  for (int r = 40; r < 72; ++r) p.logits.at<float>(r, 11) = r < 45 ? 1.5f : 0.7f;
  const cv::Mat before = p.mask.clone();
  EXPECT_EQ(cut_leg_gap(p.mask, p.logits, 1.0), 27);
  for (int r = 0; r < 72; ++r)
    for (int c = 0; c < 24; ++c)
      EXPECT_EQ(p.mask.at<uchar>(r, c), c == 11 && r >= 45 ? 0 : before.at<uchar>(r, c)) << r << "," << c;
  EXPECT_EQ(components_below(p.mask, 45), 2);  // two legs below the crotch
  // The outline goes up the slit and back: about twice its length longer.
  ContourOptions o;
  o.min_height = 1;
  o.max_border_fraction = 1.0;
  o.landmarks = 400;
  const auto length = [&](const cv::Mat& mask) { return closed_length(contour_from_mask(mask, o).points); };
  EXPECT_NEAR(length(p.mask) - length(before), 2 * 27, 6);
}

TEST(LegGap, NothingIsCutWhereTheValleyIsNotBelowTheSlitLogit) {
  Person p;
  for (int r = 36; r < 72; ++r) p.logits.at<float>(r, 11) = 1.0f;  // not strictly below 1
  const cv::Mat before = p.mask.clone();
  EXPECT_EQ(cut_leg_gap(p.mask, p.logits, 1.0), 0);
  EXPECT_EQ(cv::countNonZero(p.mask != before), 0);
  // Nor in a mask with no body in its lower half.
  cv::Mat head = cv::Mat::zeros(72, 24, CV_8UC1), logits(72, 24, CV_32FC1, cv::Scalar(-5.0f));
  head(cv::Rect(8, 0, 8, 20)).setTo(255);
  EXPECT_EQ(cut_leg_gap(head, logits, 1.0), 0);
  EXPECT_EQ(cv::countNonZero(head), 8 * 20);
}

TEST(LegGap, ADiagonalValleyGivesASlitThatSeparatesTheLegs) {
  Person p;
  // The valley steps one column right every 4 rows from (40, 8) to (71, 15).
  for (int r = 40; r < 72; ++r) p.logits.at<float>(r, 8 + (r - 40) / 4) = 0.2f;
  EXPECT_EQ(cut_leg_gap(p.mask, p.logits, 1.0), 32);
  for (int r = 40; r < 72; ++r) EXPECT_EQ(p.mask.at<uchar>(r, 8 + (r - 40) / 4), 0) << r;
  EXPECT_EQ(components_below(p.mask, 40), 2);  // no 8-connected step across the slit
  EXPECT_EQ(p.mask.at<uchar>(39, 8), 255);
}

TEST(LegGap, LegsApartStayAsTheyAreAndTheValleyNeverRunsOutsideTheBody) {
  Person p;
  // A real gap (background, -5) between the legs up to row 50, the body solid above it.
  p.mask(cv::Rect(10, 50, 4, 22)).setTo(0);
  p.logits(cv::Rect(10, 50, 4, 22)).setTo(-5.0f);
  const cv::Mat before = p.mask.clone();
  cut_leg_gap(p.mask, p.logits, 1.0);
  EXPECT_EQ(cv::countNonZero(p.mask != before), 0);
  // Outside the body the logits are lowest of all, but the valley stays inside: a solid body whose logits
  // are above the slit logit everywhere inside is not cut, however low they are beside it.
  Person solid;
  EXPECT_EQ(cut_leg_gap(solid.mask, solid.logits, 1.0), 0);
  EXPECT_EQ(cv::countNonZero(solid.mask), 16 * 72);
}

}  // namespace
}  // namespace bodyrec
