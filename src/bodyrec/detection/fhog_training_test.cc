// fHOG detector training on drawn people: the written model loads with FhogDetector and finds them.
#include "bodyrec/detection/fhog_training.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/detection/fhog_detector.h"
#include "synthetic_silhouette.h"
#include "test_support.h"

namespace bodyrec {
namespace {

std::vector<FhogTrainingImage> drawn_people(int count, uint64_t first_seed) {
  std::vector<FhogTrainingImage> images;
  for (int i = 0; i < count; ++i) {
    const auto s = testing::make_silhouette(cv::Size(200, 200), 150, first_seed + static_cast<uint64_t>(i));
    images.push_back({s.image, {Box(cv::boundingRect(s.mask))}, {}});
  }
  return images;
}

TEST(FhogTraining, TrainedModelLoadsAndFindsDrawnPeople) {
  testing::TempDir dir;
  const std::string path = (dir / "d.svm").string();
  FhogTrainOptions o;
  o.target_size = 60;
  o.flip = true;
  auto train = drawn_people(10, 1);
  train[0].boxes.push_back(Box(5, 5, 8, 8));  // far too small for the window: ignored, not an error
  const FhogTrainReport r = train_fhog_detector(train, o, path);
  EXPECT_EQ(r.boxes, 20);  // 10 people and their mirrors
  EXPECT_EQ(r.unreachable, 2);
  EXPECT_NEAR(static_cast<double>(r.window.width) * r.window.height, 60.0 * 60.0, 200.0);
  EXPECT_LT(r.window.width, r.window.height);  // people are taller than wide

  const DetectionAccuracy a = test_fhog_detector(path, drawn_people(6, 100), false);
  EXPECT_GE(a.recall, 0.8);
  EXPECT_GE(a.precision, 0.8);
  FhogOptions f;
  f.model_path = path;
  FhogDetector detector(f);
  EXPECT_EQ(detector.window_size(), r.window);
}

TEST(FhogTraining, BadOptionsAndInputs) {
  testing::TempDir dir;
  FhogTrainOptions o;
  o.C = 0;
  EXPECT_THROW(o.check(), UsageError);
  o = FhogTrainOptions{};
  o.target_size = 5;
  EXPECT_THROW(o.check(), UsageError);
  EXPECT_THROW(train_fhog_detector({}, FhogTrainOptions{}, (dir / "d.svm").string()), ProcessingError);
  EXPECT_THROW(train_fhog_detector(drawn_people(2, 1), FhogTrainOptions{}, (dir / "no" / "d.svm").string()),
               ProcessingError);
  testing::write_text(dir / "junk.svm", "junk");
  EXPECT_TRUE(testing::contains(
      testing::input_error([&] { test_fhog_detector((dir / "junk.svm").string(), drawn_people(1, 1), false); }),
      "junk.svm"));
}

}  // namespace
}  // namespace bodyrec
