// Frames nobody can process and videos with nothing to process: a 100-megapixel image or video, and a
// video without one frame, are input errors (exit 3, one line naming the file) found when the source
// opens, before any output file exists.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

// Every command that reads frames through a frame source, with OUT as its JSON-lines output.
std::vector<std::vector<std::string>> frame_commands(const fs::path& input, const fs::path& dir) {
  write_text(dir / "gt.txt", "1,1,10,10,20,40,1,1,1\n");
  write_text(dir / "roles.csv", "frame,x,y,w,h,role\n0,10,10,20,40,leader\n");
  const std::string in = input.string(), out = (dir / "out.jsonl").string();
  return {{"detect", in, "--jsonl", out, "--mot", (dir / "out.txt").string()},
          {"track", in, "--jsonl", out, "--annotate", (dir / "annotated").string()},
          {"groups", in, "--jsonl", out},
          {"eval", "detect", "--source", in, "--gt", (dir / "gt.txt").string(), "--jsonl", out},
          {"eval", "track", "--source", in, "--gt", (dir / "gt.txt").string(), "--jsonl", out},
          {"eval", "roles", "--source", in, "--gt", (dir / "roles.csv").string(), "--jsonl", out}};
}

void expect_refused_without_output(const fs::path& input, const fs::path& dir, const std::string& message) {
  for (const auto& args : frame_commands(input, dir)) {
    SCOPED_TRACE(args[0] + " " + args[1]);
    const RunResult r = run_bodyrec(args);
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_EQ(r.err, "bodyrec: error: " + message + "\n");
    for (const char* output : {"out.jsonl", "out.txt", "annotated"}) EXPECT_FALSE(fs::exists(dir / output)) << output;
  }
}

TEST(FrameLimits, AHundredMegapixelImageIsRefusedBeforeAnyOutput) {
  TempDir dir;
  const fs::path big = dir / "big.jpg";
  ASSERT_TRUE(cv::imwrite(big.string(), cv::Mat(10000, 10000, CV_8UC1, cv::Scalar(0))));
  expect_refused_without_output(big, dir.path(),
                                big.string() + ": 10000x10000 pixels (100.0 MP) exceeds the 64 MP limit per frame");
  // In a folder after a good image: the good frame is written, the big one stops the run naming it.
  fs::create_directories(dir / "frames");
  ASSERT_TRUE(cv::imwrite((dir / "frames" / "a.png").string(), cv::Mat(96, 64, CV_8UC3, cv::Scalar(40, 80, 120))));
  fs::rename(big, dir / "frames" / "b.jpg");
  const RunResult r = run_bodyrec({"detect", (dir / "frames").string(), "--preset", "thesis", "--levels", "1",
                                   "--jsonl", (dir / "d.jsonl").string(), "-q"});
  expect_one_line_error(r, 3,
                        (dir / "frames" / "b.jpg").string() +
                            ": 10000x10000 pixels (100.0 MP) exceeds the 64 MP limit per frame (frame 1)");
  EXPECT_EQ(lines_of(read_text(dir / "d.jsonl")).size(), 1u);
}

TEST(FrameLimits, AHundredMegapixelVideoIsRefusedBeforeAnyOutput) {
  TempDir dir;
  const fs::path big = dir / "big.avi";
  {
    cv::VideoWriter video(big.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25, cv::Size(10000, 7000));
    ASSERT_TRUE(video.isOpened());
    video.write(cv::Mat(7000, 10000, CV_8UC3, cv::Scalar(0, 0, 0)));
  }
  expect_refused_without_output(big, dir.path(),
                                big.string() + ": 10000x7000 pixels (70.0 MP) exceeds the 64 MP limit per frame");
}

// A recording whose colour images are 100 MP: refused from meta.json when it opens.
TEST(FrameLimits, ARecordingWithHundredMegapixelColourIsRefusedWhenItOpens) {
  TempDir dir;
  const fs::path made = synth_recording({"--frames", "2", "--people", "1", "--seed", "3"});
  const fs::path rec = dir / "rec";
  fs::copy(made, rec, fs::copy_options::recursive);
  nlohmann::json meta = nlohmann::json::parse(read_text(rec / "meta.json"));
  meta["color_intrinsics"]["width"] = 10000;
  meta["color_intrinsics"]["height"] = 10000;
  write_text(rec / "meta.json", meta.dump(2));
  const std::string message = (rec / "meta.json").string() +
                              ": color_intrinsics: 10000x10000 pixels (100.0 MP) exceeds the 64 MP limit per frame";
  for (const char* command : {"orient", "segment", "contour", "reid"}) {
    SCOPED_TRACE(command);
    std::vector<std::string> args = {command, rec.string(), "--jsonl", (dir / "out.jsonl").string()};
    if (std::string(command) == "reid") args.insert(args.end(), {"--gallery", (dir / "g.db").string()});
    const RunResult r = run_bodyrec(args);
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_EQ(r.err, "bodyrec: error: " + message + "\n");
    EXPECT_FALSE(fs::exists(dir / "out.jsonl"));
    EXPECT_FALSE(fs::exists(dir / "g.db"));
  }
}

TEST(FrameLimits, AVideoWithoutAFrameIsRefusedLikeAnEmptyFile) {
  TempDir dir;
  const fs::path none = dir / "none.avi";
  {
    cv::VideoWriter video(none.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25, cv::Size(64, 48));
    ASSERT_TRUE(video.isOpened());
  }
  ASSERT_GT(fs::file_size(none), 0u);  // a valid AVI header: not an empty file
  expect_refused_without_output(none, dir.path(), "video has no decodable frame: " + none.string());
}

}  // namespace
}  // namespace bodyrec::testing
