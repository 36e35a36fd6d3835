// The DPM photo detector's box correction, its fit, the post-processing of raw boxes, and model loading.
#include "bodyrec/detection/dpm_people_detector.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "bodyrec/core/error.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using testing::contains;
using testing::input_error;

TEST(BoxCorrection, MovesTheCentreAndScalesTheSize) {
  const BoxCorrection c{0.1, -0.05, 1.2, 0.9};
  const Box b = c.apply(Box(100, 200, 50, 100));  // centre 125, 250
  EXPECT_DOUBLE_EQ(b.x + b.width / 2, 130.0);
  EXPECT_DOUBLE_EQ(b.y + b.height / 2, 245.0);
  EXPECT_DOUBLE_EQ(b.width, 60.0);
  EXPECT_DOUBLE_EQ(b.height, 90.0);
  EXPECT_EQ(BoxCorrection{}.apply(Box(1, 2, 3, 4)), Box(1, 2, 3, 4));
}

TEST(FitBoxCorrection, MediansOverMatchedPeople) {
  // Three people whose truth is the detection widened 10, 20 and 60 % (median 20 %) and shifted down by
  // 0, 2 and 4 % of the height (median 2 %); a fourth truth box overlaps nothing and is left out.
  std::vector<std::vector<Detection>> detections = {{{Box(0, 0, 100, 200), 1.0}, {Box(300, 0, 100, 200), 0.5}},
                                                    {{Box(0, 0, 100, 200), 2.0}}};
  const BoxCorrection wider10{0, 0.00, 1.1, 1}, wider20{0, 0.02, 1.2, 1}, wider60{0, 0.04, 1.6, 1};
  std::vector<std::vector<Box>> truth = {
      {wider10.apply(detections[0][0].box), wider60.apply(detections[0][1].box), Box(900, 900, 10, 10)},
      {wider20.apply(detections[1][0].box)}};
  const BoxCorrection c = fit_box_correction(detections, truth);
  EXPECT_NEAR(c.center_x, 0.0, 1e-12);
  EXPECT_NEAR(c.center_y, 0.02, 1e-12);
  EXPECT_NEAR(c.width, 1.2, 1e-12);
  EXPECT_NEAR(c.height, 1.0, 1e-12);
  // An even count takes the mean of the two middle values; no match at all gives the identity.
  truth[1].clear();
  EXPECT_NEAR(fit_box_correction(detections, truth).width, 1.35, 1e-12);
  const BoxCorrection none = fit_box_correction(detections, {{Box(900, 900, 10, 10)}, {}});
  EXPECT_EQ(none.apply(Box(1, 2, 3, 4)), Box(1, 2, 3, 4));
}

TEST(CorrectDetections, CorrectsClipsSuppressesAndSorts) {
  const std::vector<Detection> raw = {{Box(-20, 10, 40, 80), 0.5},    // corrected, then clipped at x = 0
                                      {Box(200, 10, 40, 80), 2.0},
                                      {Box(202, 12, 40, 80), 1.0},    // a near copy of the one above
                                      {Box(500, 10, 40, 80), 3.0}};   // outside the 320-px frame
  const auto out = correct_detections(raw, BoxCorrection{0, 0, 1.5, 1}, cv::Size(320, 240), 0.4);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_DOUBLE_EQ(out[0].score, 2.0);
  EXPECT_EQ(out[0].box, Box(190, 10, 60, 80));
  EXPECT_EQ(out[1].box, Box(0, 10, 30, 80));  // x from [-30, 30) clipped to [0, 30)
}

TEST(DpmPeopleDetector, MissingOrForeignModelFileIsAnInputErrorNamingIt) {
  testing::TempDir dir;
  DpmOptions o;
  o.model_path = (dir / "none.xml").string();
  EXPECT_TRUE(contains(input_error([&] { DpmPeopleDetector d(o); }), "none.xml"));
  o.model_path = (dir / "model.txt").string();
  testing::write_text(o.model_path, "<opencv_storage></opencv_storage>\n");
  EXPECT_TRUE(contains(input_error([&] { DpmPeopleDetector d(o); }), "model.txt"));
  o.model_path = (dir / "model.xml").string();
  testing::write_text(o.model_path, "<?xml version=\"1.0\"?>\n<opencv_storage>\n<SBin>8</SBin>\n</opencv_storage>\n");
  EXPECT_TRUE(contains(input_error([&] { DpmPeopleDetector d(o); }), "model.xml"));
  testing::write_text(o.model_path, "<?xml version=\"1.0\"?>\n<opencv_storage>\n<SBin>8</Bin>\n");  // not XML
  EXPECT_TRUE(contains(input_error([&] { DpmPeopleDetector d(o); }), "model.xml"));
  o.model_path.clear();
  EXPECT_THROW(DpmPeopleDetector{o}, UsageError);
}

TEST(DpmPeopleDetector, ModelWithAFieldCutIsAnInputErrorNamingTheField) {
  const std::string debian = "/usr/share/doc/opencv-doc/examples/dpm/data/inriaperson.xml";
  if (!std::filesystem::exists(debian)) GTEST_SKIP() << "opencv-doc's inriaperson.xml missing (scripts/install-deps)";
  const std::string text = testing::read_text(debian);
  const size_t begin = text.find("<Anchor>"), end = text.find("</Anchor>");
  ASSERT_NE(begin, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  testing::TempDir dir;
  DpmOptions o;
  o.model_path = (dir / "cut.xml").string();
  testing::write_text(o.model_path, text.substr(0, begin) + text.substr(end + 9));
  const std::string message = input_error([&] { DpmPeopleDetector d(o); });
  EXPECT_TRUE(contains(message, "cut.xml")) << message;
  EXPECT_TRUE(contains(message, "Anchor")) << message;
  o.model_path = debian;
  EXPECT_NO_THROW(DpmPeopleDetector{o});
}

TEST(DpmPeopleDetector, PhotoPresetFindsNobodyOnABlankImageAndLeavesTheImageAlone) {
  if (!std::filesystem::exists("/usr/share/doc/opencv-doc/examples/dpm/data/inriaperson.xml"))
    GTEST_SKIP() << "opencv-doc's inriaperson.xml missing (scripts/install-deps)";
  DpmPeopleDetector detector(dpm_photo_preset());
  const cv::Mat frame(240, 320, CV_8UC3, cv::Scalar(90, 120, 150));
  const cv::Mat before = frame.clone();
  EXPECT_TRUE(detector.detect(frame).empty());
  EXPECT_EQ(frame.type(), CV_8UC3);
  EXPECT_EQ(cv::norm(frame, before, cv::NORM_INF), 0.0);
  EXPECT_TRUE(contains(detector.describe(), "inriaperson.xml"));
}

TEST(DpmPeopleDetector, ImagesSmallerThanItsPyramidNeedsFindNobodyInsteadOfFailing) {
  if (!std::filesystem::exists("/usr/share/doc/opencv-doc/examples/dpm/data/inriaperson.xml"))
    GTEST_SKIP() << "opencv-doc's inriaperson.xml missing (scripts/install-deps)";
  DpmPeopleDetector detector(dpm_photo_preset());
  // OpenCV's DPM alone throws on these (no pyramid level, or a negative size).
  for (const cv::Size size : {cv::Size(120, 160), cv::Size(400, 80), cv::Size(60, 60), cv::Size(1, 1)})
    EXPECT_TRUE(detector.detect(cv::Mat(size, CV_8UC3, cv::Scalar(90, 120, 150))).empty()) << size;
}

}  // namespace
}  // namespace bodyrec
