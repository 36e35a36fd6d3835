// The real ground-truth files bodyrec must read: PETS 2009 S2L1 (CVML XML) and MOT17 gt.txt.
#include <set>

#include <gtest/gtest.h>

#include "bodyrec/io/ground_truth.h"
#include "test_support.h"

namespace bodyrec {
namespace {

TEST(GroundTruthData, Pets2009S2L1) {
  BODYREC_REQUIRE_DATA(path, "pets09_s2l1/PETS2009-S2L1.xml");
  const GroundTruth gt = read_ground_truth(path.string());
  EXPECT_EQ(gt.frame_count, 795);  // every frame of View_001 (vtest.avi) is listed
  EXPECT_EQ(gt.boxes.size(), 4650u);
  std::set<int> ids;
  for (const auto& b : gt.boxes) {
    ids.insert(b.id);
    EXPECT_GE(b.frame, 0);
    EXPECT_LT(b.frame, 795);
    EXPECT_GT(b.box.width, 0);
    EXPECT_GT(b.box.height, 0);
    EXPECT_FALSE(b.ignore);
  }
  EXPECT_EQ(ids.size(), 19u);
  EXPECT_EQ(read_cvml(path.string()).boxes.size(), 4650u);
}

TEST(GroundTruthData, Mot17MiniGroundTruth) {
  BODYREC_REQUIRE_DATA(path, "mot17_mini/train/MOT17-02-FRCNN/gt/gt.txt");
  const GroundTruth gt = read_mot(path.string(), true);
  ASSERT_EQ(gt.boxes.size(), 156u);
  EXPECT_EQ(gt.frame_count, 4);  // frames 1..4 on disk
  int ignored = 0;
  std::set<int> ids;
  for (const auto& b : gt.boxes) {
    ignored += b.ignore;
    ids.insert(b.id);
  }
  EXPECT_EQ(ignored, 68);  // conf 0: static people, vehicles, occluders
  EXPECT_EQ(ids.size(), 39u);
  const auto frames = gt.by_frame();
  ASSERT_EQ(frames.size(), 4u);
  for (const auto& [frame, boxes] : frames) EXPECT_EQ(boxes.size(), 39u) << "frame " << frame;
  // First row: 1,1,912,484,97,109,0,7,1.0 -> frame 0, id 1, ignored.
  EXPECT_EQ(gt.boxes[0].frame, 0);
  EXPECT_EQ(gt.boxes[0].id, 1);
  EXPECT_EQ(gt.boxes[0].box, Box(912, 484, 97, 109));
  EXPECT_TRUE(gt.boxes[0].ignore);
  // Read as results, nothing is ignored and conf becomes the score.
  const GroundTruth results = read_mot(path.string(), false);
  ASSERT_EQ(results.boxes.size(), 156u);
  for (const auto& b : results.boxes) EXPECT_FALSE(b.ignore);
  EXPECT_DOUBLE_EQ(results.boxes[0].score, 0.0);
}

}  // namespace
}  // namespace bodyrec
