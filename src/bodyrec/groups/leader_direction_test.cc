#include "bodyrec/groups/leader_direction.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

namespace bodyrec {
namespace {

// A smooth random texture (a "person") shifted by (dx, dy) pixels on a plain background.
cv::Mat textured(double dx, double dy) {
  static const cv::Mat texture = [] {
    cv::Mat t(140, 80, CV_8UC1);
    cv::RNG rng(7);
    rng.fill(t, cv::RNG::UNIFORM, 0, 255);
    cv::GaussianBlur(t, t, {0, 0}, 2.5);
    cv::normalize(t, t, 20, 235, cv::NORM_MINMAX);
    return t;
  }();
  cv::Mat img(300, 300, CV_8UC1, cv::Scalar(128));
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 100 + dx, 0, 1, 60 + dy);
  cv::warpAffine(texture, img, shift, img.size(), cv::INTER_LINEAR, cv::BORDER_TRANSPARENT);
  return img;
}

TEST(LeaderDirection, Degrees) {
  EXPECT_DOUBLE_EQ(flow_degrees({1, 0}), 0);
  EXPECT_DOUBLE_EQ(flow_degrees({0, -1}), 90);  // image up
  EXPECT_DOUBLE_EQ(flow_degrees({-1, 0}), 180);
  EXPECT_DOUBLE_EQ(flow_degrees({0, 1}), 270);
}

TEST(LeaderDirection, FlowAtTheTorsoOfAPersonWalkingRightAndUp) {
  LeaderDirection direction;
  std::optional<Direction> d;
  cv::Mat previous = textured(0, 0);
  for (int f = 1; f <= 5; ++f) {
    cv::Mat current = textured(2.0 * f, -1.0 * f);
    d = direction.update(previous, current, Box(100 + 2.0 * f, 60 - 1.0 * f, 80, 140));
    previous = current;
  }
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->samples, 5);
  EXPECT_NEAR(d->flow.x, 2.0, 0.35);
  EXPECT_NEAR(d->flow.y, -1.0, 0.35);
  EXPECT_NEAR(d->degrees, 26.6, 8.0);
  EXPECT_NEAR(d->magnitude, std::sqrt(5.0), 0.4);
  EXPECT_NEAR(d->torso.x, 110 + 40, 1e-9);
}

TEST(LeaderDirection, AveragesOnlyTheLastWindowFrames) {
  LeaderDirectionOptions o;
  o.window = 3;
  LeaderDirection direction(o);
  std::optional<Direction> d;
  cv::Mat previous = textured(0, 0);
  double x = 0;
  // Three frames moving left, then three moving right: the window forgets the left moves.
  for (int f = 1; f <= 6; ++f) {
    x += f <= 3 ? -2.0 : 2.0;
    cv::Mat current = textured(x, 0);
    d = direction.update(previous, current, Box(100 + x, 60, 80, 140));
    previous = current;
  }
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->samples, 3);
  EXPECT_NEAR(d->flow.x, 2.0, 0.35);
  EXPECT_NEAR(d->degrees < 180 ? d->degrees : d->degrees - 360, 0.0, 10.0);
  direction.reset();
  d = direction.update(previous, previous, Box(100 + x, 60, 80, 140));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->samples, 1);
  EXPECT_NEAR(d->magnitude, 0.0, 0.05);
}

TEST(LeaderDirection, EmptyOrOutsideBoxGivesNothing) {
  LeaderDirection direction;
  const cv::Mat a = textured(0, 0);
  EXPECT_FALSE(direction.update(a, a, Box(400, 400, 50, 100)).has_value());
  EXPECT_FALSE(direction.update(cv::Mat(), a, Box(100, 60, 80, 140)).has_value());
}

}  // namespace
}  // namespace bodyrec
