// The PETS 2009 calibration against the PETS ground truth: walking speeds on the ground plane.
#include <map>

#include <gtest/gtest.h>

#include "bodyrec/io/ground_plane.h"
#include "bodyrec/io/ground_truth.h"
#include "test_support.h"

namespace bodyrec {
namespace {

TEST(GroundPlaneData, PetsPeopleWalkAtHumanSpeeds) {
  BODYREC_REQUIRE_DATA(calibration, "pets09_s2l1/View_001.xml");
  BODYREC_REQUIRE_DATA(gt, "pets09_s2l1/PETS2009-S2L1.xml");
  const auto plane = read_tsai_calibration(calibration.string());
  const GroundTruth truth = read_ground_truth(gt.string());
  std::map<int, std::vector<LabelledBox>> by_id;
  for (const auto& b : truth.boxes) by_id[b.id].push_back(b);
  ASSERT_EQ(by_id.size(), 19u);
  // Straight-line speed over 2 s (14 frames at the recording's 7 fps) for every person, every 14 frames.
  int windows = 0, human = 0;
  for (const auto& [id, boxes] : by_id)
    for (size_t i = 0; i + 14 < boxes.size(); i += 14) {
      if (boxes[i + 14].frame - boxes[i].frame != 14) continue;
      auto foot = [&](const LabelledBox& b) {
        return plane->to_ground({b.box.x + b.box.width / 2, b.box.y + b.box.height});
      };
      const double speed = cv::norm(foot(boxes[i + 14]) - foot(boxes[i])) / 2.0;
      ++windows;
      human += speed < 2.5;
    }
  EXPECT_GT(windows, 250);
  EXPECT_GE(human, windows * 98 / 100) << human << " of " << windows;
  // Person 1 crosses the scene: over its whole track it covers 10-20 m on the ground.
  const auto& p1 = by_id.at(1);
  const auto a = plane->to_ground({p1.front().box.x + p1.front().box.width / 2, p1.front().box.y + p1.front().box.height});
  const auto z = plane->to_ground({p1.back().box.x + p1.back().box.width / 2, p1.back().box.y + p1.back().box.height});
  EXPECT_NEAR(cv::norm(a - z), 10.5, 1.0);
}

}  // namespace
}  // namespace bodyrec
