// The whole group-leader pipeline on a scripted scene: two people walking side by side and one walking the
// other way alone, detected on blank frames (no motion), 10 frames per second, 100 px per metre.
#include "bodyrec/groups/group_pipeline.h"

#include <map>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// Boxes of 170 px people (1.7 m at 100 px per metre): A and B walk right side by side, 0.8 m apart,
// at 1.2 m/s; C walks left alone, 4 m away from them.
class WalkersDetector : public PeopleDetector {
 public:
  std::vector<Detection> detect(const cv::Mat&) override {
    const double t = frame++ / 10.0;
    return {{Box(50 + 120 * t, 100, 60, 170), 1.0},   // A
            {Box(50 + 120 * t, 180, 60, 170), 1.0},   // B, 0.8 m below A in the image
            {Box(1900 - 120 * t, 580, 60, 170), 1.0}};  // C
  }
  std::string describe() const override { return "walkers"; }
  int frame = 0;
};

TEST(GroupPipeline, TwoWalkingTogetherAreAGroupWithALeaderAndTheThirdANonMember) {
  WalkersDetector detector;
  GroupPipelineOptions o;
  o.tracking.detect_every = 1;
  o.stages.pixels_per_metre = 100;
  GroupPipeline pipeline(detector, o, nullptr);
  const cv::Mat blank(800, 2000, CV_8UC3, cv::Scalar(0, 0, 0));
  GroupPipelineResult last;
  for (int i = 0; i < 100; ++i) {
    Frame f;
    f.index = i;
    f.time_s = i / 10.0;
    f.image = blank;
    last = pipeline.process(f);
    EXPECT_TRUE(last.detected);
    EXPECT_DOUBLE_EQ(last.time_s, i / 10.0);
  }
  ASSERT_EQ(last.tracks.size(), 3u);
  ASSERT_EQ(last.groups.people.size(), 3u);
  std::map<int, PersonView> by_id;
  for (const PersonView& p : last.groups.people) by_id[p.id] = p;
  // Track ids are given in detection order at confirmation: A 1, B 2, C 3.
  const PersonView &a = by_id.at(1), &b = by_id.at(2), &c = by_id.at(3);
  EXPECT_GE(a.group, 0);
  EXPECT_EQ(a.group, b.group);
  EXPECT_EQ(c.group, -1);
  EXPECT_EQ(c.role, Role::kNonMember);
  const int leaders = (a.role == Role::kLeader) + (b.role == Role::kLeader);
  EXPECT_EQ(leaders, 1);
  EXPECT_TRUE(a.role == Role::kMember || b.role == Role::kMember);
  ASSERT_EQ(last.groups.leaders.size(), 1u);
  EXPECT_EQ(last.groups.leaders[0].group, a.group);
}

TEST(GroupPipeline, TheFpsOptionSetsTheTimeBase) {
  WalkersDetector detector;
  GroupPipelineOptions o;
  o.fps = 7;
  o.stages.pixels_per_metre = 100;
  GroupPipeline pipeline(detector, o, nullptr);
  Frame f;
  f.index = 14;
  f.time_s = 1.4;  // what a header saying 10 fps gives
  f.image = cv::Mat(800, 2000, CV_8UC3, cv::Scalar(0, 0, 0));
  EXPECT_DOUBLE_EQ(pipeline.process(f).time_s, 2.0);
}

TEST(GroupPipeline, OptionsAreCheckedWithTheFieldNamed) {
  WalkersDetector detector;
  GroupPipelineOptions o;
  o.fps = -1;
  try {
    GroupPipeline pipeline(detector, o, nullptr);
    FAIL() << "a negative fps was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("GroupPipelineOptions.fps"), std::string::npos) << e.what();
  }
  o = {};
  o.tracking.detect_every = 0;
  EXPECT_THROW(GroupPipeline(detector, o, nullptr), UsageError);
  EXPECT_EQ(parse_role_mode("voting"), RoleMode::kVoting);
  EXPECT_FALSE(parse_role_mode("vote"));
  EXPECT_STREQ(to_string(RoleMode::kThesis), "thesis");
}

}  // namespace
}  // namespace bodyrec
