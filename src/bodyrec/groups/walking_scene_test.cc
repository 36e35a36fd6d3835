// Parsers for EWAP/UCY obsmat.txt and groups.txt, including broken input.
#include "bodyrec/groups/walking_scene.h"

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

const char* const kRow = "   7.8000000e+02   1.0000000e+00   8.4568443e+00   0.0000000e+00   3.5880664e+00   1.6717144e+00   0.0000000e+00   1.7629183e-01\n";

TEST(ReadObsmat, ReadsRowsInFrameOrderWithXyFromColumns3And5) {
  TempDir dir;
  write_text(dir / "obsmat.txt", std::string("786 1 9.1 0 3.6 1.6 0 0.3\n\n") + kRow + "780 2 1 0 2 0 0 -1\n");
  const auto rows = read_obsmat((dir / "obsmat.txt").string());
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].frame, 780);
  EXPECT_EQ(rows[0].person, 1);
  EXPECT_DOUBLE_EQ(rows[0].position.x, 8.4568443);
  EXPECT_DOUBLE_EQ(rows[0].position.y, 3.5880664);
  EXPECT_DOUBLE_EQ(rows[0].velocity.y, 0.17629183);
  EXPECT_EQ(rows[1].person, 2);
  EXPECT_EQ(rows[2].frame, 786);
}

TEST(ReadObsmat, BrokenInputNamesFileLineAndField) {
  TempDir dir;
  const auto path = dir / "obsmat.txt";
  const auto error_for = [&](const std::string& text) {
    write_text(path, text);
    return input_error([&] { read_obsmat(path.string()); });
  };
  std::string e = error_for(std::string(kRow) + "781 1 2 0 3 1 0\n");
  EXPECT_TRUE(contains(e, "obsmat.txt:2: expected 8 fields")) << e;
  e = error_for("780 1 abc 0 3 1 0 1\n");
  EXPECT_TRUE(contains(e, ":1: field 'pos_x' is not a finite number: 'abc'")) << e;
  e = error_for("780 1 1 0 nan 1 0 1\n");
  EXPECT_TRUE(contains(e, "field 'pos_y'")) << e;
  e = error_for("780 1.5 1 0 1 1 0 1\n");
  EXPECT_TRUE(contains(e, "field 'ped' is not a non-negative integer")) << e;
  e = error_for("-6 1 1 0 1 1 0 1\n");
  EXPECT_TRUE(contains(e, "field 'frame'")) << e;
  e = error_for("6 1 1 0 1 1 0 1\n6 1 2 0 1 1 0 1\n");
  EXPECT_TRUE(contains(e, ":2: person 1 appears twice in frame 6")) << e;
  e = error_for("\n\n");
  EXPECT_TRUE(contains(e, "no trajectory rows")) << e;
  e = input_error([&] { read_obsmat((dir / "missing.txt").string()); });
  EXPECT_TRUE(contains(e, "missing.txt: no such file")) << e;
}

TEST(ReadGroups, KeepsLinesAsSetsAndToleratesRepeatsAndOverlaps) {
  TempDir dir;
  // Like seq_eth's lines 36-38: an id repeated on a line and people on two lines.
  write_text(dir / "groups.txt", " 240 239 238 237\n 241 242 238 238\n\n 7\n");
  const auto groups = read_groups((dir / "groups.txt").string());
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[1], (std::vector<int>{241, 242, 238}));
  EXPECT_EQ(groups[2], (std::vector<int>{7}));
}

TEST(ReadGroups, BrokenIdsNameFileAndLine) {
  TempDir dir;
  write_text(dir / "groups.txt", "1 2\n3 x4\n");
  std::string e = input_error([&] { read_groups((dir / "groups.txt").string()); });
  EXPECT_TRUE(contains(e, "groups.txt:2: person id is not a non-negative integer: 'x4'")) << e;
  write_text(dir / "groups.txt", "1 -2\n");
  e = input_error([&] { read_groups((dir / "groups.txt").string()); });
  EXPECT_TRUE(contains(e, "groups.txt:1:")) << e;
}

TEST(ReadWalkingScene, EstimatesTheFramePeriodFromVelocitiesAndLabelsPairs) {
  TempDir dir;
  std::string obsmat;
  // Person 1 walks 0.6 m per 10 frames at 1.5 m/s: 0.04 s per frame (25 fps); person 2 beside, 3 far.
  for (int k = 0; k < 12; ++k) {
    const std::string f = std::to_string(10 * k), x = std::to_string(0.6 * k);
    obsmat += f + " 1 " + x + " 0 0 1.5 0 0\n" + f + " 2 " + x + " 0 0.8 1.5 0 0\n" + f + " 3 5 0 9 0 0 0\n";
  }
  write_text(dir / "obsmat.txt", obsmat);
  write_text(dir / "groups.txt", "1 2\n3\n");
  const WalkingScene scene = read_walking_scene(dir.path().string());
  EXPECT_NEAR(scene.seconds_per_frame, 0.04, 1e-9);
  EXPECT_EQ(scene.rows.size(), 36u);
  ASSERT_EQ(scene.groups.size(), 1u);  // the singleton line is not a group
  EXPECT_TRUE(scene.together(2, 1));
  EXPECT_FALSE(scene.together(1, 3));
  EXPECT_EQ(read_walking_scene(dir.path().string(), 0.1).seconds_per_frame, 0.1);
  const std::string e = input_error([&] { read_walking_scene((dir / "nothing").string()); });
  EXPECT_TRUE(contains(e, "not a scene folder")) << e;
}

// Found reading the code behind the obsmat fuzz target: positions near the double range made ratios of
// inf / inf = NaN that went into the median, and people standing still with non-zero velocities gave a
// period of 0 (every frame at time 0). The period is now always finite and positive, or an InputError.
TEST(EstimateSecondsPerFrame, SkipsOverflowingSamplesAndRefusesAZeroPeriod) {
  std::vector<ObsmatRow> rows;
  for (int k = 0; k < 12; ++k) {
    rows.push_back({10 * k, 1, {0.6 * k, 0}, {1.5, 0}});                    // 0.04 s per frame
    rows.push_back({10 * k, 5, {k % 2 ? 1e308 : -1e308, 0}, {1e308, 0}});  // |2e308| / inf: NaN
    rows.push_back({10 * k, 6, {k % 2 ? 1e308 : -1e308, 0}, {1.5, 0}});    // inf / 15: inf
  }
  std::sort(rows.begin(), rows.end(), [](const ObsmatRow& a, const ObsmatRow& b) {
    return a.frame != b.frame ? a.frame < b.frame : a.person < b.person;
  });
  EXPECT_NEAR(estimate_seconds_per_frame(rows, "obsmat.txt"), 0.04, 1e-12);

  std::vector<ObsmatRow> still;
  for (int k = 0; k < 12; ++k) still.push_back({10 * k, 1, {2, 3}, {1.5, 0}});
  EXPECT_EQ(input_error([&] { estimate_seconds_per_frame(still, "obsmat.txt"); }),
            "obsmat.txt: the frame period estimated from 11 moving samples is 0 (positions do not change while "
            "velocities say they do); give it explicitly");
  still.resize(10);
  EXPECT_EQ(input_error([&] { estimate_seconds_per_frame(still, "obsmat.txt"); }),
            "obsmat.txt: too few moving samples (9) to estimate the frame period; give it explicitly");
}

}  // namespace
}  // namespace bodyrec::testing
