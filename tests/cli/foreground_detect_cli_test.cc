// `--preset foreground` (background subtraction) in the detection and tracking commands: a static
// camera's image sequence with one person-like figure walking right, 5 pixels per frame.
#include <filesystem>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"
#include "walking_figure.h"

namespace bodyrec::testing {
namespace {

TEST(ForegroundDetectCli, TracksTheOneMovingFigureOfAStaticCamera) {
  TempDir dir;
  const std::string frames = walking_figure(dir / "frames").string();
  const RunResult r = run_bodyrec({"track", frames, "--preset", "foreground", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 40u);
  std::set<int> ids;
  for (const std::string& line : lines) {
    const nlohmann::json frame = nlohmann::json::parse(line);
    for (const auto& t : frame["tracks"]) ids.insert(t["id"].get<int>());
  }
  EXPECT_EQ(ids, std::set<int>{1});  // one person, one track
  const nlohmann::json last = nlohmann::json::parse(lines.back())["tracks"];
  ASSERT_EQ(last.size(), 1u);
  const nlohmann::json box = last[0]["box"];  // the figure is at 215, 100, 30 x 90
  EXPECT_NEAR(box[0].get<double>(), 215, 3);
  EXPECT_NEAR(box[1].get<double>(), 100, 3);
  EXPECT_NEAR(box[2].get<double>(), 30, 3);
  EXPECT_NEAR(box[3].get<double>(), 90, 3);
}

// --preset auto: a command that tracks reads a folder of images as one sequence (the video preset, HOG
// around moving regions); detect reads it as unrelated photos (the photo detector).
TEST(ForegroundDetectCli, AutoPresetTakesAFolderAsASequenceWhenTracking) {
  TempDir dir;
  const std::string frames = walking_figure(dir / "frames").string();
  const RunResult track = run_bodyrec({"track", frames, "--max-frames", "3", "--jsonl", (dir / "t.jsonl").string()});
  ASSERT_EQ(track.exit_code, 0) << track.err;
  EXPECT_TRUE(contains(track.err, "OpenCV HOG")) << track.err;
  EXPECT_TRUE(contains(track.err, "motion regions")) << track.err;
  const RunResult photo = run_bodyrec({"detect", frames, "--max-frames", "1", "--jsonl", (dir / "d.jsonl").string()});
  ASSERT_EQ(photo.exit_code, 0) << photo.err;
  EXPECT_TRUE(contains(photo.err, "DPM")) << photo.err;
}

// A shorter run into a folder of annotated frames says that the earlier run's later frames are still there.
TEST(ForegroundDetectCli, AShorterRunIntoAnAnnotatedFolderNamesTheEarlierFramesLeft) {
  TempDir dir;
  const std::string frames = walking_figure(dir / "frames").string();
  const std::string out = (dir / "annotated").string();
  const RunResult first = run_bodyrec({"detect", frames, "--preset", "opencv", "--max-frames", "10", "--annotate", out, "-q"});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_FALSE(contains(first.err, "note:")) << first.err;
  const RunResult second = run_bodyrec({"detect", frames, "--preset", "opencv", "--max-frames", "4", "--annotate", out, "-q"});
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_EQ(second.err, "bodyrec: note: " + out +
                            " holds 6 frame files of an earlier run that this run did not replace (000004.png ... "
                            "000009.png)\n");
  EXPECT_TRUE(std::filesystem::exists(dir / "annotated" / "000009.png"));
}

TEST(ForegroundDetectCli, HogOptionsAreRefused) {
  TempDir dir;
  const std::string frames = walking_figure(dir / "frames").string();
  expect_one_line_error(run_bodyrec({"detect", frames, "--preset", "foreground", "--hit-threshold", "0.5", "-q"}), 2,
                        "--hit-threshold");
  expect_one_line_error(run_bodyrec({"track", frames, "--preset", "foreground", "--roi", "0", "0", "50", "50", "-q"}), 2,
                        "--roi");
  expect_one_line_error(run_bodyrec({"reid", frames, "--detector", "hog", "--preset", "foreground", "--gallery",
                                     (dir / "g.db").string()}),
                        2, "--detector foreground");
  expect_one_line_error(run_bodyrec({"detect", frames, "--preset", "foreground", "--nms-iou", "0.3", "-q"}), 2,
                        "--nms-iou");
  expect_one_line_error(run_bodyrec({"track", frames, "--preset", "foreground", "--local-margin", "0.2", "-q"}), 2,
                        "--local-margin is a HOG option");
}

// The model learns the background for 10 frames and reports nobody before: a single photo, or any input of
// 10 frames or fewer, would silently find no one.
TEST(ForegroundDetectCli, InputsShorterThanTheWarmUpAreRefused) {
  TempDir dir;
  const std::filesystem::path frames = walking_figure(dir / "frames");
  const std::string first = (frames / "000.png").string();
  ASSERT_TRUE(std::filesystem::exists(first));
  expect_one_line_error(run_bodyrec({"detect", first, "--preset", "foreground", "-q"}), 2, "the input has 1");
  expect_one_line_error(run_bodyrec({"track", frames.string(), "--preset", "foreground", "--max-frames", "10", "-q"}),
                        2, "the input has 10");
  // Eleven frames: the eleventh is the first the model reports, and it finds the figure.
  const RunResult r = run_bodyrec({"detect", frames.string(), "--preset", "foreground", "--max-frames", "11", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 11u);
  EXPECT_EQ(nlohmann::json::parse(lines[9])["detections"].size(), 0u);
  EXPECT_EQ(nlohmann::json::parse(lines[10])["detections"].size(), 1u);
}

}  // namespace
}  // namespace bodyrec::testing
