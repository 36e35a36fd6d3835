#include "bodyrec/rgbd/ground_plane.h"

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

#include "box_scene.h"

namespace bodyrec {
namespace {

using testing::person;
using testing::render;

TEST(GroundPlane, FitsTheFloorUnderALevelCameraWithPeopleOnIt) {
  const cv::Mat depth = render(person(-0.8, 3.0) + person(0.7, 2.2) + person(0.1, 4.0));
  const auto g = fit_ground_plane(depth, kinect2_depth_intrinsics(), 0.001);
  ASSERT_TRUE(g);
  EXPECT_NEAR((*g)[0], 0.0, 2e-3);
  EXPECT_NEAR((*g)[1], 1.0, 1e-4);  // normal up
  EXPECT_NEAR((*g)[2], 0.0, 2e-3);
  EXPECT_NEAR((*g)[3], 1.0, 0.005);  // the camera 1 m above it
  EXPECT_NEAR(height_above(*g, {0.3, 0.8, 3.0}), 1.8, 0.01);
  EXPECT_NEAR(height_above(*g, {0.0, -1.0, 2.0}), 0.0, 0.01);
}

TEST(GroundPlane, NoFloorInViewGivesNoneAndBadInputIsAnInputError) {
  const Intrinsics k = kinect2_depth_intrinsics();
  cv::Mat wall(k.height, k.width, CV_16U, cv::Scalar(2500));  // a wall filling the view: no floor
  EXPECT_FALSE(fit_ground_plane(wall, k, 0.001));
  EXPECT_FALSE(fit_ground_plane(cv::Mat(k.height, k.width, CV_16U, cv::Scalar(0)), k, 0.001));
  EXPECT_THROW(fit_ground_plane(cv::Mat(10, 10, CV_16U, cv::Scalar(0)), k, 0.001), InputError);
  EXPECT_THROW(fit_ground_plane(cv::Mat(k.height, k.width, CV_8U, cv::Scalar(0)), k, 0.001), InputError);
}

TEST(GroundPlaneTracker, RefitsEveryNFramesAndKeepsTheLastPlane) {
  const Intrinsics k = kinect2_depth_intrinsics();
  const cv::Mat floor = render({});
  const cv::Mat wall(k.height, k.width, CV_16U, cv::Scalar(2500));
  GroundPlaneTracker t(k, 0.001, 10);
  EXPECT_FALSE(t.update(0, wall));  // no plane yet: tried every frame
  ASSERT_TRUE(t.update(1, floor));
  EXPECT_NEAR((*t.plane())[3], 1.0, 0.005);
  // A wall in front of the camera for a while: the floor is kept.
  for (int i = 2; i < 30; ++i) ASSERT_TRUE(t.update(i, wall)) << "frame " << i;
  EXPECT_NEAR((*t.plane())[3], 1.0, 0.005);
  EXPECT_TRUE(t.update(30, cv::Mat()));  // no depth: no refit
}

}  // namespace
}  // namespace bodyrec
