#include "bodyrec/core/geometry.h"

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

TEST(Iou, IdenticalDisjointAndPartial) {
  EXPECT_DOUBLE_EQ(iou(Box(0, 0, 10, 10), Box(0, 0, 10, 10)), 1.0);
  EXPECT_DOUBLE_EQ(iou(Box(0, 0, 10, 10), Box(20, 0, 10, 10)), 0.0);
  // Overlap 5x10 = 50; union 100 + 100 - 50 = 150.
  EXPECT_DOUBLE_EQ(iou(Box(0, 0, 10, 10), Box(5, 0, 10, 10)), 50.0 / 150.0);
  // Touching edges do not overlap.
  EXPECT_DOUBLE_EQ(iou(Box(0, 0, 10, 10), Box(10, 0, 10, 10)), 0.0);
}

TEST(Iou, EmptyBoxesGiveZero) {
  EXPECT_DOUBLE_EQ(iou(Box(0, 0, 0, 10), Box(0, 0, 0, 10)), 0.0);
  EXPECT_DOUBLE_EQ(iou(Box(), Box(0, 0, 5, 5)), 0.0);
}

TEST(Iou, ContainedBox) {
  // 4x4 inside 8x8: 16 / 64.
  EXPECT_DOUBLE_EQ(iou(Box(2, 2, 4, 4), Box(0, 0, 8, 8)), 0.25);
}

TEST(NonMaxSuppression, KeepsBestOfOverlappingAndAllDisjoint) {
  std::vector<Detection> in = {{Box(0, 0, 10, 20), 0.5},
                               {Box(1, 1, 10, 20), 0.9},   // overlaps the first heavily, higher score
                               {Box(50, 0, 10, 20), 0.3},  // disjoint
                               {Box(2, 0, 10, 20), 0.1}};
  const auto out = non_max_suppression(in, 0.5);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_DOUBLE_EQ(out[0].score, 0.9);
  EXPECT_EQ(out[0].box, Box(1, 1, 10, 20));
  EXPECT_DOUBLE_EQ(out[1].score, 0.3);
}

TEST(NonMaxSuppression, ThresholdIsStrict) {
  // IoU of these two is 50/150 = 0.333...: kept under 0.34, suppressed under 0.33.
  std::vector<Detection> in = {{Box(0, 0, 10, 10), 1.0}, {Box(5, 0, 10, 10), 0.5}};
  EXPECT_EQ(non_max_suppression(in, 0.34).size(), 2u);
  EXPECT_EQ(non_max_suppression(in, 0.33).size(), 1u);
}

TEST(NonMaxSuppression, ContainmentRemovesSmallBoxInsideBigOne) {
  std::vector<Detection> in = {{Box(0, 0, 40, 80), 1.0}, {Box(10, 10, 10, 20), 0.8}};
  EXPECT_EQ(non_max_suppression(in, 0.5).size(), 2u);  // IoU = 200/3200, kept without containment
  EXPECT_EQ(non_max_suppression(in, 0.5, 0.8).size(), 1u);
}

TEST(NonMaxSuppression, EmptyInput) { EXPECT_TRUE(non_max_suppression({}, 0.5).empty()); }

TEST(Box, ScaleAndClip) {
  EXPECT_EQ(scale_box(Box(1, 2, 3, 4), 2.0), Box(2, 4, 6, 8));
  EXPECT_EQ(clip_box(Box(-5, -5, 10, 10), cv::Size(100, 100)), Box(0, 0, 5, 5));
  EXPECT_TRUE(clip_box(Box(200, 200, 10, 10), cv::Size(100, 100)).empty());
}

}  // namespace
}  // namespace bodyrec
