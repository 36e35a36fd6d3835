// `bodyrec orient` and `bodyrec eval orient` as a user meets them: on a short synthetic recording
// generated here, and with broken inputs.
#include <algorithm>
#include <filesystem>

#include <gtest/gtest.h>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

// 45 frames of 2 people crossing, seed 21 (not one of the seeds the estimator was set on).
const fs::path& synth_recording() {
  return bodyrec::testing::synth_recording(
      {"--people", "2", "--seed", "21", "--frames", "45", "--scenario", "cross"});
}

TEST(EvalOrientCli, RobustViewsMatchTheTruth) {
  const RunResult r = run_bodyrec({"eval", "orient", synth_recording().string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["frames"].get<int>(), 45);
  EXPECT_GE(j["scored"].get<int>(), 40);
  EXPECT_GE(j["accuracy"].get<double>(), 0.95);
  EXPECT_EQ(j["no_view"].get<int>(), 0);
  EXPECT_TRUE(contains(r.out, "confusion"));
  // The thesis table leaves most synthetic body-frames (side views while crossing) without a view.
  const RunResult t = run_bodyrec({"eval", "orient", synth_recording().string(), "--views", "thesis", "--face-oracle",
                                   "--json"});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_GT(last_json_line(t.out)["no_view"].get<int>(), 0);
}

TEST(OrientCli, PrintsViewsAndJsonLines) {
  TempDir dir;
  const RunResult r = run_bodyrec({"orient", synth_recording().string(), "--max-frames", "30", "--no-faces", "--jsonl",
                                   (dir / "o.jsonl").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["frames"].get<int>(), 30);
  EXPECT_GT(j["bodies"].get<int>(), 0);
  EXPECT_TRUE(contains(r.out, " view "));
  const std::string lines = read_text(dir / "o.jsonl");
  EXPECT_EQ(std::count(lines.begin(), lines.end(), '\n'), 30);
  const auto last = last_json_line(lines);
  EXPECT_EQ(last["frame"].get<int>(), 29);
  ASSERT_FALSE(last["bodies"].empty());
  const auto& b = last["bodies"][0];
  for (const char* key : {"key", "slot", "yaw_deg", "view", "confidence", "source", "face"}) EXPECT_TRUE(b.contains(key)) << key;
  // JSON lines on stdout instead of the text lines.
  const RunResult s = run_bodyrec({"orient", synth_recording().string(), "--max-frames", "3", "--no-faces", "--jsonl", "-"});
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_FALSE(contains(s.out, " view "));
  EXPECT_TRUE(contains(s.out, "\"bodies\""));
}

TEST(OrientCli, BadInputsSayWhatIsWrong) {
  TempDir dir;
  RunResult r = run_bodyrec({"orient", (dir / "missing").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  r = run_bodyrec({"orient", synth_recording().string(), "--views", "kinect"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = run_bodyrec({"orient", synth_recording().string(), "--views", "thesis", "--depth-only"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "--depth-only needs --views robust")) << r.err;
  // A broken skeleton file names the file.
  write_text(dir / "bad.skeleton", "2\n1\n72057594037934994 0 0 0 0 0 0 0.1 0.2 2\n25\n1 2 3\n");
  r = run_bodyrec({"orient", (dir / "bad.skeleton").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "bad.skeleton")) << r.err;
  // eval orient needs truth: a skeleton file has none.
  r = run_bodyrec({"eval", "orient", (dir / "bad.skeleton").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "needs a recording with truth")) << r.err;
}

}  // namespace
}  // namespace bodyrec::testing
