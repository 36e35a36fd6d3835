// Depth-only segmentation on ray-cast scenes with known geometry (tests/box_scene.h): a floor, a back
// wall and box people.
#include "bodyrec/rgbd/segment.h"

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"
#include "bodyrec/rgbd/recording.h"

#include "box_scene.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using testing::person;
using testing::render;
using testing::Slab;

TEST(DepthSegmenter, FindsTwoSeparatePeopleWithGroundAndHeights) {
  DepthSegmenter seg(kinect2_depth_intrinsics(), 0.001);
  const Segmentation s = seg.segment(render(person(-0.8, 3.0) + person(0.7, 4.0, 1.6)));
  ASSERT_TRUE(s.ground.has_value());
  EXPECT_NEAR((*s.ground)[1], 1.0, 1e-3);  // normal up
  EXPECT_NEAR((*s.ground)[3], 1.0, 0.01);  // camera 1 m above
  ASSERT_EQ(s.people.size(), 2u);
  EXPECT_EQ(s.people[0].label, 0);
  EXPECT_NEAR(s.people[0].height_m, 1.75, 0.03);
  EXPECT_NEAR(s.people[1].height_m, 1.6, 0.03);
  EXPECT_NEAR(s.people[0].centroid[2], 3.0, 0.01);
  EXPECT_NEAR(s.people[1].centroid[2], 4.0, 0.01);
  // Person 0's box: x from -1.05 to -0.55 m at 3 m -> u = 255.5 + 365.5 * x / 3 (Kinect v2 defaults).
  const Intrinsics k = kinect2_depth_intrinsics();
  EXPECT_NEAR(s.people[0].box.x, k.cx + k.fx * -1.05 / 3.0, 1.5);
  EXPECT_NEAR(s.people[0].box.br().x, k.cx + k.fx * -0.55 / 3.0, 1.5);
  // Feet within the ground tolerance are ground: the box ends above the floor line.
  EXPECT_LT(s.people[0].box.br().y, k.cy + k.fy * 1.0 / 3.0);
  EXPECT_EQ(s.labels.at<uint8_t>(static_cast<int>(k.cy), static_cast<int>(k.cx + k.fx * -0.8 / 3.0)), 0);
  EXPECT_EQ(s.labels.at<uint8_t>(static_cast<int>(k.cy), static_cast<int>(k.cx)), kNoBody);
}

TEST(DepthSegmenter, SplitsTwoTouchingPeopleAtTheirHeads) {
  DepthSegmenter seg(kinect2_depth_intrinsics(), 0.001);
  const Segmentation s = seg.segment(render(person(-0.25, 3.0) + person(0.25, 3.0, 1.7)));
  ASSERT_EQ(s.people.size(), 2u);
  EXPECT_NEAR(s.people[0].height_m, 1.75, 0.03);
  EXPECT_NEAR(s.people[1].height_m, 1.7, 0.03);
  EXPECT_NEAR(s.people[0].centroid[0], -0.25, 0.05);
  EXPECT_NEAR(s.people[1].centroid[0], 0.25, 0.05);
}

TEST(DepthSegmenter, RejectsTooShortTooTallAndTooNarrow) {
  DepthSegmenter seg(kinect2_depth_intrinsics(), 0.001);
  std::vector<Slab> scene = {{-1.5, -1.0, 0.0, 0.8, 3.0},    // a table: too low
                             {1.0, 1.6, 0.0, 2.6, 3.5},      // a cupboard up to 2.6 m: no head in range
                             {0.0, 0.04, 0.0, 1.8, 3.0}};    // a 4 cm pole
  EXPECT_TRUE(seg.segment(render(scene)).people.empty());
  EXPECT_EQ(seg.segment(render(scene + person(-0.5, 2.5))).people.size(), 1u);
}

TEST(DepthSegmenter, BackgroundModelRemovesWhatWasAlwaysThere) {
  // A person-shaped statue stands in every frame of the background.
  DepthSegmenter seg(kinect2_depth_intrinsics(), 0.001);
  const std::vector<Slab> statue = person(1.2, 4.5);
  EXPECT_EQ(seg.segment(render(statue)).people.size(), 1u);  // without background: a person
  seg.learn_background(render(statue));
  EXPECT_TRUE(seg.has_background());
  EXPECT_TRUE(seg.segment(render(statue)).people.empty());
  const Segmentation s = seg.segment(render(statue + person(-0.6, 2.5)));
  ASSERT_EQ(s.people.size(), 1u);
  EXPECT_NEAR(s.people[0].centroid[0], -0.6, 0.05);
}

TEST(DepthSegmenter, BrokenInputIsAnInputError) {
  DepthSegmenter seg(kinect2_depth_intrinsics(), 0.001);
  EXPECT_TRUE(testing::contains(testing::input_error([&] { seg.segment(cv::Mat(424, 512, CV_8U, cv::Scalar(0))); }),
                                "depth must be 16-bit 512x424"));
  EXPECT_TRUE(testing::contains(testing::input_error([&] { seg.segment(cv::Mat(10, 10, CV_16U, cv::Scalar(0))); }),
                                "512x424"));
  EXPECT_FALSE(testing::input_error([] { DepthSegmenter(Intrinsics{}, 0.001); }).empty());
  EXPECT_FALSE(testing::input_error([] { DepthSegmenter(kinect2_depth_intrinsics(), 0.0); }).empty());
  // Empty depth (no valid pixel): no ground, no people, no crash.
  const Segmentation s = seg.segment(cv::Mat(424, 512, CV_16U, cv::Scalar(0)));
  EXPECT_TRUE(s.people.empty());
  EXPECT_FALSE(s.ground.has_value());
}

TEST(MatchMasks, OptimalOneToOneIou) {
  cv::Mat truth(10, 10, CV_8U, cv::Scalar(kNoBody)), pred(10, 10, CV_8U, cv::Scalar(kNoBody));
  truth(cv::Rect(0, 0, 4, 10)).setTo(0);  // 40 px
  truth(cv::Rect(5, 0, 5, 10)).setTo(3);  // 50 px
  pred(cv::Rect(0, 0, 4, 5)).setTo(2);    // 20 px inside truth 0: IoU 0.5
  pred(cv::Rect(4, 0, 6, 10)).setTo(1);   // 60 px, 50 in truth 3: IoU 50/60
  pred(cv::Rect(0, 9, 1, 1)).setTo(5);    // 1 px inside truth 0 too: left over
  const MaskMatch m = match_masks(truth, pred);
  ASSERT_EQ(m.iou.size(), 2u);
  EXPECT_DOUBLE_EQ(m.iou[0], 0.5);
  EXPECT_DOUBLE_EQ(m.iou[1], 50.0 / 60.0);
  EXPECT_EQ(m.unmatched_predicted, 1);
  // A true person below the pixel threshold is not scored; nothing predicted: IoU 0.
  const MaskMatch none = match_masks(truth, cv::Mat(10, 10, CV_8U, cv::Scalar(kNoBody)), 45);
  ASSERT_EQ(none.iou.size(), 1u);
  EXPECT_EQ(none.iou[0], 0.0);
}

}  // namespace
}  // namespace bodyrec
