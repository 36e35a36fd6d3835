// The real files bodyrec must read: PETS 2009 ground truth, MOT17 gt.txt, the thesis author's imglab XML.
#include <set>

#include <gtest/gtest.h>

#include "bodyrec/io/ground_truth.h"
#include "bodyrec/io/imglab_xml.h"
#include "test_support.h"

namespace bodyrec {
namespace {

TEST(RealData, Pets2009GroundTruth) {
  BODYREC_REQUIRE_DATA(path, "pets09_s2l1/PETS2009-S2L1.xml");
  const GroundTruth gt = read_cvml(path.string());
  EXPECT_EQ(gt.frame_count, 795);
  EXPECT_EQ(gt.boxes.size(), 4650u);
  std::set<int> ids;
  for (const auto& b : gt.boxes) ids.insert(b.id);
  EXPECT_EQ(ids.size(), 19u);
}

TEST(RealData, Mot17GroundTruth) {
  BODYREC_REQUIRE_DATA(path, "mot17_mini/train/MOT17-02-FRCNN/gt/gt.txt");
  const GroundTruth gt = read_mot(path.string(), true);
  EXPECT_GT(gt.boxes.size(), 0u);
  int ignored = 0;
  for (const auto& b : gt.boxes) ignored += b.ignore;
  EXPECT_GT(ignored, 0);                              // this sequence has static people and vehicles
  EXPECT_LT(ignored, static_cast<int>(gt.boxes.size()));
}

TEST(RealData, ThesisAuthorsLandmarkFiles) {
  BODYREC_REQUIRE_DATA(path, "thesis_ch3/training_with_body_landmarks.xml");
  const ImglabDataset d = read_imglab(path.string());
  ASSERT_EQ(d.images.size(), 4u);
  for (const auto& image : d.images) {
    ASSERT_EQ(image.boxes.size(), 1u) << image.file;
    const auto points = ordered_parts(image.boxes[0], image.file);
    EXPECT_EQ(points.size(), 180u) << image.file;
  }
  // Part 00 is at the top of the head: the first box's point 0 is (316, 81), 15 px below the box top.
  const auto first = ordered_parts(d.images[0].boxes[0], "first");
  EXPECT_EQ(first[0], cv::Point2d(316, 81));
  EXPECT_EQ(d.images[0].boxes[0].box, Box(237, 66, 173, 368));
}

TEST(RealData, ThesisAuthorsDetectorTrainingSet) {
  BODYREC_REQUIRE_DATA(path, "thesis_ch3/mydataset8.xml");
  const ImglabDataset d = read_imglab(path.string());
  ASSERT_FALSE(d.images.empty());
  for (const auto& image : d.images)
    for (const auto& box : image.boxes) EXPECT_EQ(box.label, "body_detected") << image.file;
}

}  // namespace
}  // namespace bodyrec
