// The linear shape correction: what it learns from known linear errors, its invariance to the box, and
// its serialisation with broken input.
#include "bodyrec/landmarks/shape_correction.h"

#include <cmath>
#include <random>
#include <sstream>

#include <dlib/serialize.h>
#include <gtest/gtest.h>

#include "bodyrec/core/error.h"
#include "test_support.h"

namespace bodyrec {
namespace {

// Fitted shapes of 3 points in boxes of many sizes and places; the truth is each fitted point moved by a
// constant plus a linear function of the shape (in box units): what the correction can learn exactly.
struct Pairs {
  std::vector<std::vector<cv::Point2d>> fitted, truth;
  std::vector<Box> boxes;
};

cv::Point2d true_offset(const std::vector<cv::Point2d>& unit, size_t k) {
  // Point k moves right by 0.1 box heights and down by a fifth of how far point 0 sits from the centre.
  return {0.1, 0.2 * unit[0].x + (k == 2 ? -0.3 * unit[1].y : 0.0)};
}

Pairs linear_pairs(int people, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.2, 0.2), size(50, 300), place(0, 400);
  Pairs p;
  for (int i = 0; i < people; ++i) {
    const Box box(place(rng), place(rng), size(rng) * 0.4, size(rng));
    std::vector<cv::Point2d> unit = {{u(rng), 0.05 + u(rng) / 4}, {0.2 + u(rng), 0.5 + u(rng)}, {-0.2 + u(rng), 0.9 + u(rng) / 4}};
    std::vector<cv::Point2d> fitted, truth;
    for (size_t k = 0; k < unit.size(); ++k) {
      const cv::Point2d at(box.x + box.width / 2 + unit[k].x * box.height, box.y + unit[k].y * box.height);
      fitted.push_back(at);
      truth.push_back(at + true_offset(unit, k) * box.height);
    }
    p.fitted.push_back(fitted);
    p.truth.push_back(truth);
    p.boxes.push_back(box);
  }
  return p;
}

TEST(ShapeCorrection, LearnsALinearErrorInBoxUnits) {
  const Pairs train = linear_pairs(200, 1);
  const ShapeCorrection c = ShapeCorrection::learn(train.fitted, train.truth, train.boxes, 1e-9);
  ASSERT_FALSE(c.empty());
  EXPECT_EQ(c.landmarks(), 3);
  // Unseen people at other sizes and places: corrected onto the truth (to float weights' rounding).
  const Pairs test = linear_pairs(20, 2);
  for (size_t i = 0; i < test.fitted.size(); ++i) {
    const auto corrected = c.apply(test.fitted[i], test.boxes[i]);
    ASSERT_EQ(corrected.size(), 3u);
    for (size_t k = 0; k < 3; ++k) {
      EXPECT_NEAR(corrected[k].x, test.truth[i][k].x, 1e-3 * test.boxes[i].height) << i << " " << k;
      EXPECT_NEAR(corrected[k].y, test.truth[i][k].y, 1e-3 * test.boxes[i].height) << i << " " << k;
    }
  }
  // A strong ridge keeps only the mean error: every point moves by the training people's mean offset.
  const ShapeCorrection mean_only = ShapeCorrection::learn(train.fitted, train.truth, train.boxes, 1e9);
  const Box box(10, 20, 40, 100);
  const std::vector<cv::Point2d> shape = {{30, 25}, {50, 70}, {10, 110}};
  const auto moved = mean_only.apply(shape, box);
  double mean_dy0 = 0;
  for (size_t i = 0; i < train.fitted.size(); ++i) mean_dy0 += (train.truth[i][0].y - train.fitted[i][0].y) / train.boxes[i].height;
  mean_dy0 /= static_cast<double>(train.fitted.size());
  EXPECT_NEAR(moved[0].x - shape[0].x, 0.1 * box.height, 1e-6);
  EXPECT_NEAR(moved[0].y - shape[0].y, mean_dy0 * box.height, 1e-3);
}

TEST(ShapeCorrection, EmptyLeavesThePointsAlone) {
  const ShapeCorrection none;
  EXPECT_TRUE(none.empty());
  const std::vector<cv::Point2d> shape = {{1, 2}, {3, 4}};
  EXPECT_EQ(none.apply(shape, Box(0, 0, 10, 10)), shape);
}

TEST(ShapeCorrection, ReadsWhatItWritesAndNamesBrokenInput) {
  const Pairs train = linear_pairs(50, 3);
  const ShapeCorrection c = ShapeCorrection::learn(train.fitted, train.truth, train.boxes, 0.1);
  std::ostringstream out;
  c.write(out);
  const std::string bytes = out.str();
  std::istringstream in(bytes);
  const ShapeCorrection back = ShapeCorrection::read(in, 3, "m.dat");
  EXPECT_EQ(back.apply(train.fitted[0], train.boxes[0]), c.apply(train.fitted[0], train.boxes[0]));
  // Cut short, for another landmark count, or with a value that is not a number.
  std::istringstream cut(bytes.substr(0, bytes.size() - 3));
  const std::string truncated = testing::input_error([&] { ShapeCorrection::read(cut, 3, "m.dat"); });
  EXPECT_TRUE(testing::contains(truncated, "m.dat: truncated mask-net model (shape correction)")) << truncated;
  std::istringstream other(bytes);
  EXPECT_TRUE(testing::contains(testing::input_error([&] { ShapeCorrection::read(other, 4, "m.dat"); }),
                                "m.dat: mask-net model has an invalid shape correction"));
  std::ostringstream nan_out;
  dlib::serialize(std::vector<double>(6, 0.0), nan_out);
  dlib::serialize(std::vector<double>{0, 0, NAN, 0, 0, 0}, nan_out);
  dlib::serialize(std::vector<float>(36, 0.0f), nan_out);
  std::istringstream nan_in(nan_out.str());
  EXPECT_TRUE(testing::contains(testing::input_error([&] { ShapeCorrection::read(nan_in, 3, "n.dat"); }),
                                "n.dat: mask-net model has an invalid shape correction"));
}

TEST(ShapeCorrection, RefusesToLearnFromPointsThatAreNotNumbers) {
  Pairs bad = linear_pairs(50, 4);
  bad.truth[0][1].x = NAN;
  try {
    ShapeCorrection::learn(bad.fitted, bad.truth, bad.boxes, 0.1);
    ADD_FAILURE() << "no ProcessingError";
  } catch (const ProcessingError& e) {
    EXPECT_TRUE(testing::contains(e.what(), "shape correction: the ridge regression has no finite solution")) << e.what();
  }
}

}  // namespace
}  // namespace bodyrec
