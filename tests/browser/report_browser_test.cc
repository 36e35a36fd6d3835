// The report in a real browser: headless Chromium renders the page to a PNG and we check that the plots,
// the embedded key frames and the gallery's scans are on it. Skips with a message when `chromium` is not
// installed.
#include <algorithm>
#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

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

// Mask of pixels close to the gallery scans' cyan (BGR 255, 255, 0).
cv::Mat cyan_mask(const cv::Mat& image) {
  cv::Mat mask;
  cv::inRange(image, cv::Scalar(200, 200, 0), cv::Scalar(255, 255, 70), mask);
  return mask;
}

// Bounding boxes of the cyan regions of at least `min_area` pixels, top to bottom, left to right.
std::vector<cv::Rect> cyan_blobs(const cv::Mat& image, int min_area) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(cyan_mask(image), labels, stats, centroids, 8);
  std::vector<cv::Rect> blobs;
  for (int i = 1; i < n; ++i)
    if (stats.at<int>(i, cv::CC_STAT_AREA) >= min_area)
      blobs.emplace_back(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                         stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT));
  std::sort(blobs.begin(), blobs.end(), [](const cv::Rect& a, const cv::Rect& b) {
    return std::make_pair(a.y / 20, a.x) < std::make_pair(b.y / 20, b.x);
  });
  return blobs;
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

TEST(ReportBrowser, ChromiumRendersGalleryRows) {
  if (!have_chromium()) GTEST_SKIP() << "chromium not installed (scripts/install-deps installs it when it can)";
  TempDir dir;
  const RunResult r = report_with_gallery(dir, "report.html");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const cv::Mat shot = screenshot(dir / "report.html", dir / "shot.png");
  ASSERT_FALSE(shot.empty()) << "chromium did not write a screenshot";
  if (const char* keep = std::getenv("BODYREC_KEEP_GALLERY_SCREENSHOT")) cv::imwrite(keep, shot);
  // The 4 scans (cyan bodies, each filling most of a 1:2 slot) are drawn: alice's F, SR, B in one row
  // left to right, bob's BL below; all thumbnails the same height.
  const auto blobs = cyan_blobs(shot, 3000);
  ASSERT_EQ(blobs.size(), 4u) << "cyan pixels: " << cv::countNonZero(cyan_mask(shot));
  for (const auto& b : blobs) {
    EXPECT_GT(b.height, 120) << b;
    EXPECT_NEAR(b.height, blobs[0].height, 3) << b;
    EXPECT_NEAR(b.height, 2.2 * b.width, 0.5 * b.width) << b;  // the ellipse's 116 x 52 proportions
    // Non-blank: the body is cyan and the slot around it is not.
    const cv::Rect around = (b + cv::Size(16, 16) - cv::Point(8, 8)) & cv::Rect(0, 0, shot.cols, shot.rows);
    EXPECT_LT(cv::countNonZero(cyan_mask(shot(around))), around.area() * 0.8) << b;
  }
  EXPECT_NEAR(blobs[0].y, blobs[2].y, 3);
  EXPECT_LT(blobs[0].x, blobs[1].x);
  EXPECT_LT(blobs[1].x, blobs[2].x);
  EXPECT_GT(blobs[3].y, blobs[0].y + blobs[0].height);
  // Slot order F FR FL SR SL B BR BL: SR is 3 slots right of F, B 2 more, and bob's BL in the last column.
  const double step = (blobs[2].x - blobs[0].x) / 5.0;
  EXPECT_NEAR(blobs[1].x - blobs[0].x, 3 * step, 4);
  EXPECT_NEAR(blobs[3].x - blobs[0].x, 7 * step, 4);

  const RunResult hidden = report_with_gallery(dir, "hidden.html", {"--no-images"});
  ASSERT_EQ(hidden.exit_code, 0) << hidden.err;
  const cv::Mat hidden_shot = screenshot(dir / "hidden.html", dir / "hidden.png");
  ASSERT_FALSE(hidden_shot.empty());
  if (const char* keep = std::getenv("BODYREC_KEEP_GALLERY_SCREENSHOT"))
    cv::imwrite(std::string(keep) + ".no-images.png", hidden_shot);
  EXPECT_EQ(cv::countNonZero(cyan_mask(hidden_shot)), 0);
}

}  // namespace
}  // namespace bodyrec::testing
