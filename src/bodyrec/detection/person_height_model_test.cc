#include "bodyrec/detection/person_height_model.h"

#include <cmath>

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

TEST(PersonHeightModel, LearnsTheLineOfAFlatFloor) {
  PersonHeightModel model(20);
  // Height = 0.25 * foot row + 10, with +-5 % noise alternating.
  for (int i = 0; i < 19; ++i) model.add(200 + 10 * i, (0.25 * (200 + 10 * i) + 10) * (i % 2 ? 1.05 : 0.95));
  EXPECT_FALSE(model.height_at(300));  // 19 < 20 samples
  model.add(400, 110);
  ASSERT_TRUE(model.height_at(300));
  EXPECT_NEAR(*model.height_at(300), 85, 3);
  const auto range = model.height_range(200, 400, 0.2);
  ASSERT_TRUE(range);
  EXPECT_NEAR(range->first, 60 * 0.8, 3);
  EXPECT_NEAR(range->second, 110 * 1.2, 4);
}

TEST(PersonHeightModel, RefusesScenesThatAreNotOneFloor) {
  PersonHeightModel model(20);
  // Heights unrelated to the row (a moving camera, stairs, mixed scales): residuals too large.
  for (int i = 0; i < 40; ++i) model.add(300, i % 2 ? 50 : 150);
  EXPECT_FALSE(model.height_at(300));
  EXPECT_FALSE(model.height_range(0, 500, 0.3));
}

TEST(PersonHeightModel, IgnoresBadSamplesAndKeepsTheMostRecent) {
  PersonHeightModel model(4, 10);
  model.add(100, -5);
  model.add(std::nan(""), 50);
  for (int i = 0; i < 10; ++i) model.add(100 + i, 40);   // old scene
  for (int i = 0; i < 20; ++i) model.add(100 + i % 10, 80);  // camera moved: only these are kept (refit every 10)
  ASSERT_TRUE(model.height_at(105));
  EXPECT_NEAR(*model.height_at(105), 80, 1e-6);
}

}  // namespace
}  // namespace bodyrec
