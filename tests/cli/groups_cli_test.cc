// `bodyrec groups` and `bodyrec eval roles` on the command line: output rows, summary, option and input errors.
#include <set>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

#define REQUIRE_VTEST() \
  if (!std::filesystem::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)"

TEST(GroupsCli, WritesRolesGroupsLeadersPerFrameAndASummary) {
  REQUIRE_VTEST();
  TempDir dir;
  const auto jsonl = dir / "g.jsonl";
  const auto frames_dir = dir / "frames";
  const RunResult r = run_bodyrec({"groups", vtest_path().string(), "--max-frames", "40", "--fps", "7", "--jsonl",
                                   jsonl.string(), "--annotate", frames_dir.string(), "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = last_json_line(r.out);
  EXPECT_EQ(summary["frames"].get<int>(), 40);
  EXPECT_GT(summary["ms_per_frame"].get<double>(), 0);
  for (const char* stage : {"tracking", "motion", "groups", "roles", "leader", "flow"})
    EXPECT_TRUE(summary["ms"].contains(stage)) << stage;

  const std::set<std::string> roles = {"leader", "member", "non-member", "potential-member", "unknown"};
  std::istringstream lines(read_text(jsonl));
  std::string line;
  int frames = 0, people = 0, motion_valid = 0;
  while (std::getline(lines, line)) {
    const auto row = nlohmann::json::parse(line);
    EXPECT_EQ(row["frame"].get<int>(), frames);
    EXPECT_NEAR(row["time"].get<double>(), frames / 7.0, 1e-3);  // --fps 7 sets the time base
    motion_valid += row["motion"]["valid"].get<bool>();
    for (const auto& p : row["people"]) {
      EXPECT_EQ(roles.count(p["role"].get<std::string>()), 1u) << p.dump();
      EXPECT_EQ(p["box"].size(), 4u);
      EXPECT_FALSE(p.contains("ground"));  // no calibration given
      ++people;
    }
    for (const auto& l : row["leaders"]) {
      const auto state = l["state"].get<std::string>();
      EXPECT_TRUE(state == "tracking" || state == "lost" || state == "none") << state;
    }
    ++frames;
  }
  EXPECT_EQ(frames, 40);
  EXPECT_GT(people, 100);       // 5-8 people per frame on vtest.avi once confirmed
  EXPECT_GT(motion_valid, 30);  // the three-frame stage is ready from frame 2
  // The annotated frames are written as PNG files.
  EXPECT_TRUE(std::filesystem::exists(frames_dir / "000039.png"));
}

TEST(GroupsCli, OptionAndInputErrors) {
  REQUIRE_VTEST();
  TempDir dir;
  RunResult r = run_bodyrec({"groups", vtest_path().string(), "--roles", "boss", "-q"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = run_bodyrec({"groups", vtest_path().string(), "--homography", (dir / "h.txt").string(), "-q"});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "h.txt: cannot open the homography file")) << r.err;
  write_text(dir / "h.txt", "1 0 0\n0 1 0\n0 0 1\n");
  r = run_bodyrec({"groups", vtest_path().string(), "--homography", (dir / "h.txt").string(), "--calibration",
                   (dir / "h.txt").string(), "-q"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "not both")) << r.err;
  r = run_bodyrec({"groups", vtest_path().string(), "--leader-min-psr", "-1", "-q"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
}

TEST(GroupsCli, HomographyGivesGroundPositions) {
  REQUIRE_VTEST();
  TempDir dir;
  write_text(dir / "h.txt", "0.01 0 0\n0 0.01 0\n0 0 1\n");  // 100 px per metre
  const RunResult r = run_bodyrec({"groups", vtest_path().string(), "--max-frames", "8", "--homography",
                                   (dir / "h.txt").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(r.out);
  std::string line;
  int checked = 0;
  while (std::getline(lines, line)) {
    const auto row = nlohmann::json::parse(line);  // kept: iterating a temporary's member would dangle
    for (const auto& p : row["people"]) {
      const auto box = p["box"];
      const double foot_x = box[0].get<double>() + box[2].get<double>() / 2;
      const double foot_y = box[1].get<double>() + box[3].get<double>();
      EXPECT_NEAR(p["ground"][0].get<double>(), foot_x / 100, 0.006);
      EXPECT_NEAR(p["ground"][1].get<double>(), foot_y / 100, 0.006);
      ++checked;
    }
  }
  EXPECT_GT(checked, 5);
}

TEST(EvalRolesCli, ScoresHandLabelsAndRejectsBrokenCsv) {
  REQUIRE_VTEST();
  TempDir dir;
  // Two labelled boxes nobody can match (off the image) and nothing else: accuracy 0, 0 matched.
  write_text(dir / "r.csv", "frame,x,y,w,h,role\n5,2000,2000,30,60,leader\n5,2100,2000,30,60,non-member\n");
  RunResult r = run_bodyrec({"eval", "roles", "--source", vtest_path().string(), "--max-frames", "10", "--gt",
                             (dir / "r.csv").string(), "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["boxes"].get<int>(), 2);
  EXPECT_EQ(j["matched"].get<int>(), 0);
  EXPECT_EQ(j["frames"].get<int>(), 1);
  EXPECT_DOUBLE_EQ(j["accuracy"].get<double>(), 0.0);
  EXPECT_EQ(j["confusion"]["leader"]["missed"].get<int>(), 1);

  write_text(dir / "bad.csv", "frame,x,y,w,h,role\n5,1,2,3\n");
  r = run_bodyrec({"eval", "roles", "--source", vtest_path().string(), "--gt", (dir / "bad.csv").string(), "-q"});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "bad.csv:2: expected 6 fields")) << r.err;
  r = run_bodyrec({"eval", "roles", "--gt", (dir / "r.csv").string(), "-q"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
}

}  // namespace
}  // namespace bodyrec::testing
