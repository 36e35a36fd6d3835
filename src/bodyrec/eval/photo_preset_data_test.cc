// How the photo preset's box correction was chosen and fitted, reproduced on the Penn-Fudan training split
// only (the test split is never read here): 4-fold cross-validation inside the training images says whether
// correcting the DPM's root windows helps on images the fit did not see, and the fit on all of them gives
// the constants in dpm_photo_preset().
#include <cstdio>
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/detection/dpm_people_detector.h"
#include "bodyrec/eval/detection_metrics.h"
#include "bodyrec/io/pennfudan.h"
#include "test_support.h"

namespace bodyrec {
namespace {

double fold_ap(const std::vector<PennFudanImage>& images, const std::vector<std::vector<Detection>>& raw,
               const std::vector<cv::Size>& sizes, int fold, const BoxCorrection& correction) {
  DetectionEvaluator evaluator;
  for (size_t i = 0; i < images.size(); ++i) {
    if (static_cast<int>(i % 4) != fold) continue;
    std::vector<LabelledBox> truth;
    for (const Box& b : images[i].people) truth.push_back({static_cast<int>(i), -1, b, 1.0, false});
    evaluator.add_frame(correct_detections(raw[i], correction, sizes[i], DpmOptions{}.nms_iou), truth);
  }
  return evaluator.scores().ap;
}

TEST(PhotoPresetData, BoxCorrectionChosenByCrossValidationInsideTheTrainingSplit) {
  BODYREC_REQUIRE_DATA(root, "pennfudan/PNGImages");
  if (!std::filesystem::exists("/usr/share/doc/opencv-doc/examples/dpm/data/inriaperson.xml"))
    GTEST_SKIP() << "opencv-doc's inriaperson.xml missing (scripts/install-deps)";
  const auto images = load_pennfudan(root.parent_path().string(), PennFudanSplit::kTrain);
  ASSERT_EQ(images.size(), 128u);
  const DpmOptions preset = dpm_photo_preset();
  DpmPeopleDetector detector(preset);
  std::vector<std::vector<Detection>> raw;
  std::vector<std::vector<Box>> truth;
  std::vector<cv::Size> sizes;
  for (const auto& image : images) {
    const cv::Mat frame = cv::imread(image.image_path, cv::IMREAD_COLOR);
    ASSERT_FALSE(frame.empty()) << image.image_path;
    raw.push_back(detector.detect_raw(frame));
    truth.push_back(image.people);
    sizes.push_back(frame.size());
  }
  // Each fold: fitted on the other three, scored on this one, against no correction.
  const double expected_plain[4] = {0.8798, 0.8001, 0.8394, 0.7723};
  const double expected_corrected[4] = {0.8942, 0.8290, 0.8672, 0.7904};
  for (int fold = 0; fold < 4; ++fold) {
    std::vector<std::vector<Detection>> fit_raw;
    std::vector<std::vector<Box>> fit_truth;
    for (size_t i = 0; i < images.size(); ++i)
      if (static_cast<int>(i % 4) != fold) {
        fit_raw.push_back(raw[i]);
        fit_truth.push_back(truth[i]);
      }
    const BoxCorrection c = fit_box_correction(fit_raw, fit_truth);
    const double plain = fold_ap(images, raw, sizes, fold, BoxCorrection{});
    const double corrected = fold_ap(images, raw, sizes, fold, c);
    std::printf("fold %d: correction %.4f %.4f %.4f %.4f, held-out AP50 %.4f without, %.4f with\n", fold, c.center_x,
                c.center_y, c.width, c.height, plain, corrected);
    EXPECT_GT(corrected, plain) << "fold " << fold;
    EXPECT_NEAR(plain, expected_plain[fold], 1e-4) << "fold " << fold;
    EXPECT_NEAR(corrected, expected_corrected[fold], 1e-4) << "fold " << fold;
  }
  // The preset's constants: the fit on the whole training split, to the three decimals written there.
  const BoxCorrection all = fit_box_correction(raw, truth);
  std::printf("all training images: correction %.4f %.4f %.4f %.4f\n", all.center_x, all.center_y, all.width,
              all.height);
  EXPECT_NEAR(preset.correction.center_x, all.center_x, 5e-4);
  EXPECT_NEAR(preset.correction.center_y, all.center_y, 5e-4);
  EXPECT_NEAR(preset.correction.width, all.width, 5e-4);
  EXPECT_NEAR(preset.correction.height, all.height, 5e-4);
}

}  // namespace
}  // namespace bodyrec
