#include "bodyrec/detection/hog_people_detector.h"

#include <algorithm>
#include <filesystem>
#include <tuple>

#include <gtest/gtest.h>
#include <opencv2/videoio.hpp>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "test_support.h"

namespace bodyrec {
namespace {

TEST(HogPreset, ThesisPresetIsTheThesisCall) {
  const HogOptions o = hog_preset(HogPreset::kThesis);
  EXPECT_DOUBLE_EQ(o.hit_threshold, -0.2);
  EXPECT_EQ(o.win_stride, 12);
  EXPECT_EQ(o.padding, 16);
  EXPECT_DOUBLE_EQ(o.scale, 1.05);
  EXPECT_EQ(o.group_threshold, 2);
  EXPECT_DOUBLE_EQ(o.resize, 1.0);
  EXPECT_FALSE(o.motion_roi);
}

TEST(HogPreset, DefaultSearchesSixtyToHundredFortyPixelPeople) {
  const HogOptions o = hog_preset(HogPreset::kDefault);
  // The body is 0.75 of the 128-px window: 96 px at scale 1. A 60-px person needs a 1.6x resize.
  EXPECT_NEAR(o.resize, 1.6, 1e-9);
  // Levels reach 140 px: 1.08^(levels-1) >= 140/60.
  EXPECT_GE(std::pow(o.scale, o.levels - 1), 140.0 / 60.0);
  EXPECT_LT(std::pow(o.scale, o.levels - 2), 140.0 / 60.0);
  EXPECT_TRUE(o.motion_roi);
}

TEST(HogPreset, OpenCvPresetIsThePeopledetectSample) {
  const HogOptions o = hog_preset(HogPreset::kOpenCv);
  EXPECT_DOUBLE_EQ(o.hit_threshold, 0.0);
  EXPECT_EQ(o.win_stride, 8);
  EXPECT_EQ(o.padding, 0);
  EXPECT_DOUBLE_EQ(o.scale, 1.05);
  EXPECT_EQ(o.group_threshold, 2);
  EXPECT_FALSE(o.motion_roi);
  // The sample's shrink: x + 10 %, y + 7 %, 80 % of the width and height.
  const Box body = HogPeopleDetector(o).body_box(Box(100, 200, 64, 128));
  EXPECT_NEAR(body.x, 106.4, 1e-9);
  EXPECT_NEAR(body.y, 208.96, 1e-9);
  EXPECT_NEAR(body.width, 51.2, 1e-9);
  EXPECT_NEAR(body.height, 102.4, 1e-9);
}

TEST(HogPreset, UnknownPresetAndBadOptionsAreUsageErrors) {
  EXPECT_FALSE(parse_hog_preset("fast"));
  EXPECT_EQ(parse_hog_preset("opencv"), HogPreset::kOpenCv);
  EXPECT_EQ(parse_hog_model("daimler"), HogModel::kDaimler);
  HogOptions o;
  o.scale = 1.0;
  EXPECT_THROW(o.check(), UsageError);
  o = HogOptions();
  o.win_stride = 0;
  EXPECT_THROW(HogPeopleDetector{o}, UsageError);
}

TEST(HogPeopleDetector, BodyBoxIsShrunkFromTheWindow) {
  HogPeopleDetector detector(hog_preset(HogPreset::kThesis));
  const Box body = detector.body_box(Box(100, 200, 64, 128));
  EXPECT_NEAR(body.width, 32, 1e-9);
  EXPECT_NEAR(body.height, 96, 1e-9);
  EXPECT_NEAR(body.x + body.width / 2, 100 + 0.52 * 64, 1e-9);
  EXPECT_NEAR(body.y + body.height / 2, 200 + 0.48 * 128, 1e-9);
}

TEST(HogPeopleDetector, BlankFrameHasNoPeopleAndTinyFrameDoesNotCrash) {
  HogPeopleDetector detector(hog_preset(HogPreset::kThesis));
  EXPECT_TRUE(detector.detect(cv::Mat(240, 320, CV_8UC3, cv::Scalar(128, 128, 128))).empty());
  EXPECT_TRUE(detector.detect(cv::Mat(10, 10, CV_8UC3, cv::Scalar(0, 0, 0))).empty());
  HogPeopleDetector with_motion(hog_preset(HogPreset::kDefault));
  for (int i = 0; i < 3; ++i)
    EXPECT_TRUE(with_motion.detect(cv::Mat(240, 320, CV_8UC3, cv::Scalar(90, 90, 90))).empty());
}

TEST(HogPeopleDetector, DetectNearFindsThePeopleTheFullSearchFoundAndNothingElse) {
  if (!std::filesystem::exists(testing::vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  cv::VideoCapture video(testing::vtest_path().string());
  cv::Mat frame;
  ASSERT_TRUE(video.read(frame));
  HogPeopleDetector detector(hog_preset(HogPreset::kDefault));
  const auto full = detector.detect(frame);  // first frame: the whole frame is searched
  ASSERT_GE(full.size(), 5u);
  std::vector<Box> expected;
  for (const Detection& d : full) expected.push_back(d.box);
  const auto near = detector.detect_near(frame, expected);
  int refound = 0;
  for (const Detection& d : full) {
    double best = 0;
    for (const Detection& n : near) best = std::max(best, iou(d.box, n.box));
    refound += best >= 0.5;
  }
  EXPECT_GE(refound, static_cast<int>(full.size()) - 1);
  EXPECT_LE(near.size(), full.size() + 1);
  EXPECT_TRUE(detector.detect_near(frame, {}).empty());
  // Degenerate and off-frame boxes are skipped, not searched.
  EXPECT_TRUE(detector.detect_near(frame, {Box(0, 0, 0, 0), Box(5000, 5000, 40, 80)}).empty());
}

// Our pyramid (level by level, so that each score stays with its window) gives what OpenCV's
// detectMultiScale gives when it runs on one thread, where its race cannot pair them wrongly.
TEST(HogPeopleDetector, RawWindowsAreOpenCvsWithTheirOwnScores) {
  if (!std::filesystem::exists(testing::vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  cv::VideoCapture video(testing::vtest_path().string());
  cv::Mat frame;
  ASSERT_TRUE(video.read(frame));
  HogOptions o = hog_preset(HogPreset::kThesis);
  o.group_threshold = 0;
  HogPeopleDetector detector(o);
  const std::vector<Detection> ours = detector.detect_windows(frame, cv::Rect(0, 0, frame.cols, frame.rows));

  cv::HOGDescriptor hog;
  hog.setSVMDetector(cv::HOGDescriptor::getDefaultPeopleDetector());
  hog.nlevels = o.levels;
  std::vector<cv::Rect> rects;
  std::vector<double> weights;
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  hog.detectMultiScale(frame, rects, weights, o.hit_threshold, cv::Size(o.win_stride, o.win_stride),
                       cv::Size(o.padding, o.padding), o.scale, 0);
  cv::setNumThreads(threads);

  using Window = std::tuple<int, int, int, int, double>;
  std::vector<Window> theirs, mine;
  for (size_t i = 0; i < rects.size(); ++i)
    theirs.emplace_back(rects[i].x, rects[i].y, rects[i].width, rects[i].height, weights[i]);
  for (const Detection& d : ours)
    mine.emplace_back(cvRound(d.box.x), cvRound(d.box.y), cvRound(d.box.width), cvRound(d.box.height), d.score);
  std::sort(theirs.begin(), theirs.end());
  std::sort(mine.begin(), mine.end());
  ASSERT_GE(theirs.size(), 15u);  // people in the first frame, some found by several windows
  EXPECT_EQ(mine, theirs);
}

TEST(MergeOverlapping, MergesChainsAndKeepsDisjoint) {
  const auto out = merge_overlapping({cv::Rect(0, 0, 10, 10), cv::Rect(5, 5, 10, 10), cv::Rect(12, 12, 5, 5),
                                      cv::Rect(100, 100, 5, 5)});
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0], cv::Rect(0, 0, 17, 17));
  EXPECT_EQ(out[1], cv::Rect(100, 100, 5, 5));
}

TEST(MotionRegions, FindsAMovingSquare) {
  MotionRegionOptions options;
  options.work_width = 320;
  MotionRegions motion(options);
  std::vector<cv::Rect> regions;
  for (int i = 0; i < 30; ++i) {
    cv::Mat frame(240, 320, CV_8UC3, cv::Scalar(60, 60, 60));
    cv::rectangle(frame, cv::Rect(20 + 5 * i, 100, 20, 40), cv::Scalar(230, 230, 230), cv::FILLED);
    regions = motion.update(frame);
  }
  ASSERT_EQ(regions.size(), 1u);
  const cv::Rect square(20 + 5 * 29, 100, 20, 40);
  EXPECT_EQ((regions[0] & square), square);  // the region covers the square's last position
}

}  // namespace
}  // namespace bodyrec
