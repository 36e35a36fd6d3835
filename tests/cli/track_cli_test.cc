// `bodyrec track` and `bodyrec eval track` on the command line: output formats and option errors.
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

TEST(TrackCli, WritesOneJsonLinePerFrameAndMotRowsWithIds) {
  if (!std::filesystem::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  TempDir dir;
  const auto jsonl = dir / "t.jsonl", mot = dir / "t.txt";
  const RunResult r = run_bodyrec({"track", vtest_path().string(), "--max-frames", "12", "--detect-every", "2",
                                   "--jsonl", jsonl.string(), "--mot", mot.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream lines(read_text(jsonl));
  std::string line;
  int frames = 0, boxes = 0;
  while (std::getline(lines, line)) {
    const auto row = nlohmann::json::parse(line);
    EXPECT_EQ(row["frame"].get<int>(), frames);
    EXPECT_TRUE(row.contains("time"));
    for (const auto& t : row["tracks"]) {
      EXPECT_GE(t["id"].get<int>(), 1);
      EXPECT_EQ(t["box"].size(), 4u);
      const auto state = t["state"].get<std::string>();
      EXPECT_TRUE(state == "confirmed" || state == "lost") << state;
      ++boxes;
    }
    ++frames;
  }
  EXPECT_EQ(frames, 12);
  EXPECT_GT(boxes, 0);  // people are confirmed within 12 frames of vtest.avi
  // Each MOT row carries a track id (column 2), not -1.
  std::istringstream rows(read_text(mot));
  int mot_rows = 0;
  while (std::getline(rows, line)) {
    std::istringstream cells(line);
    std::string frame, id;
    std::getline(cells, frame, ',');
    std::getline(cells, id, ',');
    EXPECT_GE(std::stoi(id), 1) << line;
    ++mot_rows;
  }
  EXPECT_EQ(mot_rows, boxes);
}

TEST(TrackCli, BadTrackerOptionsAreUsageErrors) {
  if (!std::filesystem::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  RunResult r = run_bodyrec({"track", vtest_path().string(), "--detect-every", "0", "-q"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = run_bodyrec({"track", vtest_path().string(), "--iou-gate", "1.5", "-q"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  expect_one_line_error(r, 2, "--iou-gate must be in (0, 1]");
}

TEST(TrackCli, EvalTrackNeedsGroundTruthAndSource) {
  RunResult r = run_bodyrec({"eval", "track", "--source", "x.avi"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  TempDir dir;
  r = run_bodyrec({"eval", "track", "--source", vtest_path().string(), "--gt", (dir / "missing.xml").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("missing.xml"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace bodyrec::testing
