// SIGINT (Ctrl-C) or SIGTERM in the middle of `detect` and `groups` on a video, as on a live camera: the run
// ends after its frame with exit 0, every output whole to its last frame (the annotated video's header
// counts exactly the frames written) and the summary written.
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/videoio.hpp>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

int video_frames(const fs::path& path) {
  cv::VideoCapture video(path.string());
  return video.isOpened() ? static_cast<int>(video.get(cv::CAP_PROP_FRAME_COUNT)) : -1;
}

int whole_json_lines(const fs::path& path) {
  int n = 0;
  for (const std::string& line : lines_of(read_text(path))) {
    EXPECT_TRUE(nlohmann::json::accept(line)) << line;
    ++n;
  }
  return n;
}

TEST(StopSignalCli, DetectAndGroupsEndCleanlyOnASignal) {
  if (!fs::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  TempDir dir;
  // vtest.avi has 795 frames; both commands take well over 4 s for them.
  const RunResult detect = run_bodyrec({"detect", vtest_path().string(), "--jsonl", (dir / "d.jsonl").string(),
                                        "--annotate", (dir / "d.avi").string(), "-q"},
                                       {"timeout", "--preserve-status", "-s", "INT", "4"});
  ASSERT_EQ(detect.exit_code, 0) << detect.err;
  EXPECT_TRUE(contains(detect.err, "bodyrec detect: stopped by a signal after ")) << detect.err;
  const int detected = whole_json_lines(dir / "d.jsonl");
  EXPECT_GT(detected, 0);
  EXPECT_LT(detected, 795);
  EXPECT_EQ(video_frames(dir / "d.avi"), detected);

  const RunResult groups = run_bodyrec({"groups", vtest_path().string(), "--jsonl", (dir / "g.jsonl").string(),
                                        "--annotate", (dir / "g.avi").string(), "--json", "-q"},
                                       {"timeout", "--preserve-status", "-s", "TERM", "4"});
  ASSERT_EQ(groups.exit_code, 0) << groups.err;
  const auto summary = last_json_line(groups.out);
  EXPECT_TRUE(summary["stopped"].get<bool>());
  const int frames = summary["frames"].get<int>();
  EXPECT_GT(frames, 0);
  EXPECT_LT(frames, 795);
  EXPECT_EQ(whole_json_lines(dir / "g.jsonl"), frames);
  EXPECT_EQ(video_frames(dir / "g.avi"), frames);
}

}  // namespace
}  // namespace bodyrec::testing
