// A shape model trained in-test on drawn silhouettes recovers the landmarks of unseen ones.
#include "bodyrec/landmarks/shape_training.h"

#include <filesystem>
#include <iostream>

#include <gtest/gtest.h>

#include "bodyrec/landmarks/contour.h"
#include "bodyrec/landmarks/landmark_metrics.h"
#include "silhouette_dataset.h"
#include "test_support.h"

namespace bodyrec {
namespace {

LandmarkDataset synthetic_people(int count, uint64_t first_seed, int landmarks) {
  return testing::silhouette_dataset(count, first_seed, landmarks, cv::Size(140, 170), 140, "synthetic");
}


ShapeTrainOptions small_options() {
  ShapeTrainOptions o;
  o.method = ShapeMethod::kTrees;
  o.oversampling = 20;
  o.cascade_depth = 8;
  o.trees_per_level = 150;
  o.tree_depth = 3;
  o.feature_pool_size = 200;
  o.threads = 2;
  return o;
}

TEST(ShapeTraining, RecoversLandmarksOfUnseenSilhouettes) {
  const LandmarkDataset train = synthetic_people(40, 100, 40);
  const LandmarkDataset test = synthetic_people(8, 900, 40);
  const BodyShapeModel model = train_body_shape(train, small_options());
  EXPECT_EQ(model.landmarks(), 40);
  const LandmarkScores fit = evaluate_body_shape(model, test, "synthetic");
  EXPECT_EQ(fit.persons, 8);
  // People are 140 px tall; the mean shape alone is off by about 6 px (checked below).
  std::cout << "synthetic fit: " << fit.mean_px << " px, to contour " << fit.contour_px << " px\n";
  EXPECT_LT(fit.mean_px, 3.5);
  EXPECT_LT(fit.contour_px, 2.0);

  std::vector<PersonLandmarkError> mean_shape;  // baseline: the average training shape in each box
  std::vector<cv::Point2d> average(40);
  for (const auto& image : train.images)
    for (int i = 0; i < 40; ++i) {
      const auto& p = image.people[0];
      average[static_cast<size_t>(i)] += cv::Point2d((p.landmarks[static_cast<size_t>(i)].x - p.box.x) / p.box.width,
                                                     (p.landmarks[static_cast<size_t>(i)].y - p.box.y) / p.box.height) *
                                         (1.0 / 40);
    }
  for (const auto& image : test.images) {
    const auto& p = image.people[0];
    std::vector<cv::Point2d> guess;
    for (const auto& a : average) guess.emplace_back(p.box.x + a.x * p.box.width, p.box.y + a.y * p.box.height);
    mean_shape.push_back(person_landmark_error(guess, p.landmarks, p.box, image.image.cols));
  }
  EXPECT_GT(summarize_landmark_errors(mean_shape).mean_px, 1.5 * fit.mean_px);
}

TEST(ShapeTraining, SavedModelLoadsAndPredictsTheSame) {
  const LandmarkDataset train = synthetic_people(6, 100, 12);
  ShapeTrainOptions o = small_options();
  o.cascade_depth = 2;
  o.trees_per_level = 5;
  const BodyShapeModel model = train_body_shape(train, o);
  testing::TempDir dir;
  save_body_shape(model, (dir / "shape.dat").string());
  const BodyShapeModel loaded((dir / "shape.dat").string());
  const cv::Mat gray = model.prepare(train.images[0].image);
  EXPECT_EQ(loaded.fit(gray, train.images[0].people[0].box), model.fit(gray, train.images[0].people[0].box));
  EXPECT_THROW(save_body_shape(model, (dir / "missing" / "shape.dat").string()), ProcessingError);
}

TEST(ShapeTraining, BadModelFilesAndOptions) {
  testing::TempDir dir;
  testing::write_text(dir / "junk.dat", "not a model");
  const std::string junk = (dir / "junk.dat").string();
  EXPECT_TRUE(testing::contains(testing::input_error([&] { BodyShapeModel m(junk); }), junk));
  EXPECT_TRUE(testing::contains(testing::input_error([&] { BodyShapeModel m((dir / "none.dat").string()); }),
                                "none.dat"));
  ShapeTrainOptions o;
  o.nu = 0;
  EXPECT_THROW(o.check(), UsageError);
  EXPECT_THROW(train_body_shape(LandmarkDataset{}, ShapeTrainOptions{}), ProcessingError);
  EXPECT_FALSE(parse_shape_method("forest"));
  EXPECT_EQ(parse_shape_method("trees"), ShapeMethod::kTrees);
}

}  // namespace
}  // namespace bodyrec
