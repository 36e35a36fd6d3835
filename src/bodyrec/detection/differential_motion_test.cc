#include "bodyrec/detection/differential_motion.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// A grey frame with a white 20x40 block at x (full size 400x300).
cv::Mat frame_with_block(int x) {
  cv::Mat f(300, 400, CV_8UC1, cv::Scalar(40));
  cv::rectangle(f, cv::Rect(x, 100, 20, 40), cv::Scalar(220), cv::FILLED);
  return f;
}

DifferentialMotionOptions full_size() {
  DifferentialMotionOptions o;
  o.work_width = 0;
  return o;
}

TEST(DifferentialMotion, NeedsThreeFrames) {
  DifferentialMotion m(full_size());
  EXPECT_FALSE(m.update(frame_with_block(10)).ready);
  EXPECT_FALSE(m.update(frame_with_block(20)).ready);
  EXPECT_TRUE(m.update(frame_with_block(30)).ready);
}

TEST(DifferentialMotion, BoxCoversWhatMovedInBothIntervals) {
  DifferentialMotion m(full_size());
  m.update(frame_with_block(100));
  m.update(frame_with_block(130));
  const MotionResult& r = m.update(frame_with_block(160));
  // d1 = |prev - next| marks 100..119 and 160..179; d2 = |next - curr| marks 130..149 and 160..179;
  // their AND is the block's new place 160..179 (the three-frame trick drops both ghosts); the 2x2
  // erosion (anchor at its centre) trims one pixel on the left and top. 741 of 120000 pixels moved: a
  // std-dev of 255 sqrt(p (1 - p)) = 20.0, just under the thesis's 20.
  ASSERT_TRUE(r.valid);
  ASSERT_TRUE(r.box.has_value());
  EXPECT_EQ(r.box->x, 161);
  EXPECT_EQ(r.box->y, 101);
  EXPECT_EQ(r.box->width, 19);
  EXPECT_EQ(r.box->height, 39);
  EXPECT_EQ(r.pixels, 19 * 39);
  EXPECT_NEAR(r.energy_in(Box(160, 100, 20, 40)), 19.0 * 39 / 800, 1e-9);
  EXPECT_EQ(r.energy_in(Box(0, 0, 50, 50)), 0.0);
}

TEST(DifferentialMotion, StillSceneHasNoMotion) {
  DifferentialMotion m(full_size());
  for (int i = 0; i < 3; ++i) m.update(frame_with_block(50));
  EXPECT_TRUE(m.result().ready);
  EXPECT_FALSE(m.result().valid);
  EXPECT_EQ(m.result().pixels, 0);
  EXPECT_FALSE(m.result().box.has_value());
}

TEST(DifferentialMotion, GlobalChangeFailsTheDeviationTest) {
  // Half the image flickers (a light switched): a big spread of motion pixels, not a person.
  DifferentialMotion m(full_size());
  for (int i = 0; i < 3; ++i) {
    cv::Mat f(300, 400, CV_8UC1, cv::Scalar(40));
    f(cv::Rect(0, 0, 200, 300)).setTo(i % 2 ? 200 : 40);
    if (i == 2) f(cv::Rect(0, 0, 200, 300)).setTo(120);
    m.update(f);
  }
  EXPECT_TRUE(m.result().ready);
  EXPECT_GT(m.result().pixels, 10000);
  EXPECT_GT(m.result().deviation, 20);
  EXPECT_FALSE(m.result().valid);
}

TEST(DifferentialMotion, WorkSizeBoxesAreInFramePixels) {
  DifferentialMotionOptions o;
  o.work_width = 200;  // half size
  o.erode = 0;
  o.max_deviation = 40;  // the block is a larger share of the smaller image
  DifferentialMotion m(o);
  m.update(frame_with_block(100));
  m.update(frame_with_block(130));
  const MotionResult& r = m.update(frame_with_block(160));
  ASSERT_TRUE(r.box.has_value());
  EXPECT_NEAR(r.box->x, 160, 2);
  EXPECT_NEAR(r.deviation, 255 * std::sqrt(200.0 / 30000 * (1 - 200.0 / 30000)), 0.5);
  EXPECT_NEAR(r.box->width, 20, 2);
  EXPECT_NEAR(r.box->height, 40, 2);
}

TEST(DifferentialMotion, BadOptionsAndSizeChange) {
  DifferentialMotionOptions o;
  o.threshold = 300;
  EXPECT_THROW(DifferentialMotion{o}, UsageError);
  DifferentialMotion m(full_size());
  m.update(frame_with_block(10));
  m.update(frame_with_block(20));
  EXPECT_THROW(m.update(cv::Mat(100, 100, CV_8UC1, cv::Scalar(0))), InputError);
}

}  // namespace
}  // namespace bodyrec
