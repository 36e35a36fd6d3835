#include <gtest/gtest.h>

#include "bodyrec/rgbd/camera.h"
#include "bodyrec/rgbd/skeleton.h"

namespace bodyrec {
namespace {

TEST(Camera, ProjectUnprojectRoundTripAndKinectConvention) {
  const Intrinsics k = kinect2_depth_intrinsics();
  const cv::Vec3d p(0.3, 0.5, 2.0);
  const auto px = project(k, p);
  ASSERT_TRUE(px);
  EXPECT_NEAR(px->x, 255.5 + 365.5 * 0.15, 1e-9);  // +X to larger u
  EXPECT_NEAR(px->y, 211.5 - 365.5 * 0.25, 1e-9);  // +Y up: smaller v
  const cv::Vec3d back = unproject(k, px->x, px->y, 2.0);
  EXPECT_NEAR(cv::norm(back - p), 0.0, 1e-12);
  EXPECT_FALSE(project(k, {0, 0, -1}));
}

TEST(Camera, ScaledKeepsPixelCentres) {
  const Intrinsics k = scaled(kinect2_color_intrinsics(), 960, 540);
  EXPECT_DOUBLE_EQ(k.fx, 530.0);
  EXPECT_DOUBLE_EQ(k.cx, 479.5);
  EXPECT_DOUBLE_EQ(k.cy, 269.5);
}

TEST(Camera, DepthToColourMappingMatchesProjection) {
  const Intrinsics dk = kinect2_depth_intrinsics(), ck = scaled(kinect2_color_intrinsics(), 960, 540);
  Extrinsics e = kinect2_depth_to_color();
  cv::Mat depth(dk.height, dk.width, CV_16U, cv::Scalar(2000));
  depth.at<uint16_t>(10, 10) = 0;
  cv::Mat coords;
  map_depth_to_color(depth, 0.001, dk, ck, e, coords);
  EXPECT_EQ(coords.at<cv::Vec2f>(10, 10), cv::Vec2f(-1, -1));
  const cv::Vec3d p = unproject(dk, 100, 300, 2.0);
  const auto c = project(ck, e.apply(p));
  EXPECT_NEAR(coords.at<cv::Vec2f>(300, 100)[0], c->x, 1e-3);
  EXPECT_NEAR(coords.at<cv::Vec2f>(300, 100)[1], c->y, 1e-3);
  EXPECT_NEAR(c->x - (ck.cx + ck.fx * p[0] / 2.0), ck.fx * 0.052 / 2.0, 1e-9);  // 5.2 cm baseline
}

TEST(Skeleton, NamesParentsAndThesisYaw) {
  EXPECT_STREQ(joint_names()[idx(Joint::kSpineShoulder)], "SpineShoulder");
  EXPECT_EQ(joint_parent(idx(Joint::kSpineBase)), -1);
  EXPECT_EQ(joint_parent(idx(Joint::kHead)), idx(Joint::kNeck));
  EXPECT_EQ(joint_parent(idx(Joint::kShoulderLeft)), idx(Joint::kSpineShoulder));
  EXPECT_EQ(joint_from_name("KneeRight"), idx(Joint::kKneeRight));
  EXPECT_FALSE(joint_from_name("Tail"));
  EXPECT_NEAR(thesis_yaw_deg(Quaternion::about_y(30 * M_PI / 180)), 30.0, 1e-9);
  const Quaternion q = Quaternion::about_y(0.7) * Quaternion{0.9, 0.1, 0.2, 0.3};
  const Quaternion n{q.w / q.norm(), q.x / q.norm(), q.y / q.norm(), q.z / q.norm()};
  const Quaternion back = Quaternion::from_matrix(n.matrix());
  EXPECT_NEAR(std::abs(back.w * n.w + back.x * n.x + back.y * n.y + back.z * n.z), 1.0, 1e-12);
}

}  // namespace
}  // namespace bodyrec
