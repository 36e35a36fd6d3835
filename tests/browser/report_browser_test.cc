// The report in a real browser: headless Chromium renders the page to a PNG and we check that the plots
// and the embedded key frames are on it. Skips with a message when `chromium` is not installed.
#include <cstdlib>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "report_fixture.h"
#include "test_support.h"

namespace bodyrec::testing {
namespace {

bool have_chromium() { return std::system("command -v chromium >/dev/null 2>&1") == 0; }

// Renders `html` at 1280 x 2400 and returns the screenshot (BGR), empty on failure.
cv::Mat screenshot(const std::filesystem::path& html, const std::filesystem::path& png) {
  const std::string command = "timeout 180 chromium --headless --disable-gpu --no-sandbox --hide-scrollbars "
                              "--screenshot='" + png.string() + "' --window-size=1280,2400 'file://" +
                              html.string() + "' >/dev/null 2>&1";
  if (std::system(command.c_str()) != 0) return {};
  return cv::imread(png.string(), cv::IMREAD_COLOR);
}

// Pixels close to the key frames' magenta (BGR 255, 0, 255).
int magenta_pixels(const cv::Mat& image) {
  cv::Mat mask;
  cv::inRange(image, cv::Scalar(200, 0, 200), cv::Scalar(255, 60, 255), mask);
  return cv::countNonZero(mask);
}

// Pixels of the leader blue (#2563eb, BGR 235, 99, 37) used by the role timeline and the rose.
int leader_blue_pixels(const cv::Mat& image) {
  cv::Mat mask;
  cv::inRange(image, cv::Scalar(215, 80, 20), cv::Scalar(255, 120, 60), mask);
  return cv::countNonZero(mask);
}

TEST(ReportBrowser, ChromiumRendersPlotsAndKeyFrames) {
  if (!have_chromium()) GTEST_SKIP() << "chromium not installed (scripts/install-deps installs it when it can)";
  TempDir dir;
  write_groups_run(dir / "run.jsonl", 40);
  write_magenta_video(dir / "run.avi", 40);
  const RunResult r = run_bodyrec({"report", (dir / "run.jsonl").string(), "--source", (dir / "run.avi").string(),
                                   "--out", (dir / "report.html").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat shot = screenshot(dir / "report.html", dir / "shot.png");
  ASSERT_FALSE(shot.empty()) << "chromium did not write a screenshot";
  ASSERT_EQ(shot.cols, 1280);
  // The page is not blank: its top third (header, timeline, first plot) varies.
  cv::Scalar mean, stddev;
  cv::meanStdDev(shot(cv::Rect(0, 0, shot.cols, shot.rows / 3)), mean, stddev);
  EXPECT_GT(stddev[0] + stddev[1] + stddev[2], 20.0);
  // The SVG plots drew leader-blue bars and petals, and the embedded JPEG key frames show (5 frames
  // of at least 300 x 200 CSS pixels each are mostly magenta).
  EXPECT_GT(leader_blue_pixels(shot), 2000);
  EXPECT_GT(magenta_pixels(shot), 5 * 30000);
  if (const char* keep = std::getenv("BODYREC_KEEP_SCREENSHOT")) cv::imwrite(keep, shot);

  // --no-images: the same page without any person pixels.
  const RunResult hidden = run_bodyrec({"report", (dir / "run.jsonl").string(), "--source", (dir / "run.avi").string(),
                                        "--no-images", "--out", (dir / "hidden.html").string()});
  ASSERT_EQ(hidden.exit_code, 0) << hidden.err;
  const cv::Mat hidden_shot = screenshot(dir / "hidden.html", dir / "hidden.png");
  ASSERT_FALSE(hidden_shot.empty());
  EXPECT_EQ(magenta_pixels(hidden_shot), 0);
  EXPECT_GT(leader_blue_pixels(hidden_shot), 2000);
}

}  // namespace
}  // namespace bodyrec::testing
