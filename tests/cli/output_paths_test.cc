// An output path that names an input or another output is a usage error before anything is opened: the
// input is left byte for byte as it was.
#include <filesystem>

#include <gtest/gtest.h>

#include "test_support.h"
#include "walking_figure.h"

namespace bodyrec::testing {
namespace {

TEST(OutputPaths, AnOutputNamingTheInputIsRefusedAndTheInputKept) {
  TempDir dir;
  const std::filesystem::path video = walking_figure_video(dir / "figure.avi");
  const std::string before = read_text(video);
  ASSERT_GT(before.size(), 1000u);
  expect_one_line_error(run_bodyrec({"detect", video.string(), "--jsonl", video.string(), "-q"}), 2,
                        "--jsonl " + video.string() + " is also source");
  // The same file by another spelling.
  const std::string other = (dir / "." / "figure.avi").string();
  expect_one_line_error(run_bodyrec({"track", video.string(), "--annotate", other, "-q"}), 2, "--annotate");
  expect_one_line_error(run_bodyrec({"eval", "detect", "--source", video.string(), "--gt", "gt.txt", "--mot",
                                     video.string()}),
                        2, "is also --source");
  EXPECT_EQ(read_text(video), before);
}

TEST(OutputPaths, TwoOutputsInOneFileAreRefusedButDevicesAndStdoutAreShared) {
  TempDir dir;
  const std::string video = walking_figure_video(dir / "figure.avi").string(), out = (dir / "out.txt").string();
  expect_one_line_error(run_bodyrec({"detect", video, "--jsonl", out, "--mot", out, "-q"}), 2,
                        "--jsonl " + out + " is also --mot");
  EXPECT_FALSE(std::filesystem::exists(out));
  const RunResult shared = run_bodyrec({"detect", video, "--jsonl", "/dev/null", "--mot", "/dev/null", "-q"});
  EXPECT_EQ(shared.exit_code, 0) << shared.err;
  const RunResult stdout_and_file = run_bodyrec({"detect", video, "--jsonl", "-", "--mot", out, "-q"});
  EXPECT_EQ(stdout_and_file.exit_code, 0) << stdout_and_file.err;
  EXPECT_EQ(lines_of(stdout_and_file.out).size(), 40u);
}

TEST(OutputPaths, OutputsNeverOverwriteTheGallery) {
  TempDir dir;
  const std::string video = walking_figure_video(dir / "figure.avi").string(), gallery = (dir / "g.db").string();
  write_text(gallery, "not touched");
  expect_one_line_error(run_bodyrec({"reid", video, "--gallery", gallery, "--jsonl", gallery, "-q"}), 2,
                        "--jsonl " + gallery + " is also --gallery");
  expect_one_line_error(run_bodyrec({"reid", video, "--gallery", gallery, "--events-spool", gallery, "-q"}), 2,
                        "--events-spool");
  write_text(dir / "run.jsonl", "{}\n");
  expect_one_line_error(
      run_bodyrec({"report", (dir / "run.jsonl").string(), "--gallery", gallery, "--out", gallery}), 2,
      "--out " + gallery + " is also --gallery");
  EXPECT_EQ(read_text(gallery), "not touched");
}

}  // namespace
}  // namespace bodyrec::testing
