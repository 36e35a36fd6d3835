// Importers on real data: NTU RGB+D skeletons (Kinect v2) and PCL's five_people organised cloud.
#include <filesystem>
#include <map>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/rgbd/ntu_skeleton.h"
#include "bodyrec/rgbd/pcd.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using bodyrec::testing::TempDir;

TEST(NtuData, AllSamplesParseWithTheDocumentedFrameAndBodyCounts) {
  BODYREC_REQUIRE_DATA(dir, "ntu_skeleton/samples");
  // From the dataset's PROVENANCE table: frames and the most bodies in a frame.
  const std::map<std::string, std::pair<size_t, size_t>> expected = {
      {"S001C001P001R001A001", {103, 1}}, {"S001C001P001R001A011", {82, 1}}, {"S001C001P001R001A050", {74, 2}},
      {"S001C003P008R002A058", {70, 2}},  {"S002C001P003R001A003", {100, 1}}, {"S003C001P015R001A034", {71, 1}},
      {"S004C002P003R001A017", {124, 1}}, {"S017C003P020R002A054", {42, 2}}, {"S017C003P020R002A055", {66, 2}},
      {"S017C003P020R002A056", {80, 2}},  {"S017C003P020R002A057", {76, 2}}, {"S017C003P020R002A058", {65, 2}}};
  for (const auto& [name, counts] : expected) {
    SCOPED_TRACE(name);
    const NtuSkeleton s = read_ntu_skeleton((dir / (name + ".skeleton")).string());
    EXPECT_EQ(s.frames.size(), counts.first);
    size_t most = 0;
    for (const auto& f : s.frames) most = std::max(most, f.size());
    EXPECT_EQ(most, counts.second);
  }
}

TEST(NtuData, ImportKeepsJointsAndFitsKinectLikeIntrinsics) {
  BODYREC_REQUIRE_DATA(file, "ntu_skeleton/samples/S004C002P003R001A017.skeleton");
  TempDir tmp;
  double rms[2];
  EXPECT_EQ(import_ntu(file.string(), (tmp / "rec").string(), rms), 124);
  RecordingReader r((tmp / "rec").string());
  EXPECT_EQ(r.frame_count(), 124);
  const RgbdFrame f = r.read_frame(0);
  ASSERT_EQ(f.bodies.size(), 1u);
  EXPECT_EQ(f.bodies[0].tracking_id, 72057594037934994ULL);
  const BodyJoint& base = f.bodies[0].joints[idx(Joint::kSpineBase)];
  EXPECT_DOUBLE_EQ(base.position[0], 0.0003003457);
  EXPECT_DOUBLE_EQ(base.position[1], -0.3471032);
  EXPECT_DOUBLE_EQ(base.position[2], 3.177691);
  ASSERT_TRUE(base.orientation);
  EXPECT_DOUBLE_EQ(base.orientation->w, -0.3545102);
  EXPECT_FALSE(f.bodies[0].joints[idx(Joint::kHead)].orientation);  // 0 0 0 0 in the file
  // The fitted model reproduces the file's own depth projection of SpineBase (256.3827, 248.4647).
  const auto px = project(r.meta().depth, base.position);
  EXPECT_NEAR(px->x, 256.3827, 0.5);
  EXPECT_NEAR(px->y, 248.4647, 0.5);
  EXPECT_NEAR(r.meta().depth.fx, 365.5, 5.0);
  EXPECT_LT(rms[0], 0.5);
  EXPECT_LT(rms[1], 1.0);
}

TEST(NtuData, TwoBodiesTakeSlotsInOrderOfAppearance) {
  BODYREC_REQUIRE_DATA(file, "ntu_skeleton/samples/S001C001P001R001A050.skeleton");
  TempDir tmp;
  double rms[2];
  EXPECT_EQ(import_ntu(file.string(), (tmp / "rec").string(), rms), 74);
  const RgbdFrame f = RecordingReader((tmp / "rec").string()).read_frame(0);
  ASSERT_EQ(f.bodies.size(), 2u);
  EXPECT_EQ(f.bodies[0].index, 0);
  EXPECT_EQ(f.bodies[1].index, 1);
  EXPECT_DOUBLE_EQ(f.bodies[0].joints[0].position[0], -0.8514767);
  EXPECT_DOUBLE_EQ(f.bodies[0].joints[0].position[2], 3.384463);
}

TEST(PcdData, FivePeopleImportsLosslesslyAgainstTheDerivedImages) {
  BODYREC_REQUIRE_DATA(file, "pcl_people_rgbd/five_people.pcd");
  BODYREC_REQUIRE_DATA(depth_png, "pcl_people_rgbd/derived/five_people_depth_mm.png");
  BODYREC_REQUIRE_DATA(rgb_png, "pcl_people_rgbd/derived/five_people_rgb.png");
  TempDir tmp;
  double rms = 1;
  const Intrinsics k = import_pcd(file.string(), (tmp / "rec").string(), &rms);
  EXPECT_EQ(k.width, 640);
  EXPECT_EQ(k.height, 480);
  EXPECT_NEAR(k.fx, 525.0, 1e-3);
  EXPECT_NEAR(k.fy, 525.0, 1e-3);
  EXPECT_NEAR(k.cx, 319.5, 1e-3);
  EXPECT_NEAR(k.cy, 239.5, 1e-3);
  EXPECT_LT(rms, 1e-3);
  const RgbdFrame f = RecordingReader((tmp / "rec").string()).read_frame(0);
  EXPECT_EQ(cv::countNonZero(f.depth), 239075);
  double lo = 0, hi = 0;
  cv::minMaxLoc(f.depth, nullptr, &hi);
  cv::Mat valid = f.depth > 0;
  cv::minMaxLoc(f.depth, &lo, nullptr, nullptr, nullptr, valid);
  EXPECT_EQ(lo, 1759);  // PROVENANCE: 1.76 .. 9.76 m (rounded)
  EXPECT_EQ(hi, 9757);
  const cv::Mat depth_ref = cv::imread(depth_png.string(), cv::IMREAD_UNCHANGED);
  const cv::Mat rgb_ref = cv::imread(rgb_png.string(), cv::IMREAD_COLOR);
  EXPECT_EQ(cv::norm(f.depth, depth_ref, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(f.color, rgb_ref, cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace bodyrec
