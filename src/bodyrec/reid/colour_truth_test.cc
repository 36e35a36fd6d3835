#include "bodyrec/reid/colour_truth.h"

#include <gtest/gtest.h>

#include "bodyrec/rgbd/synth.h"

namespace bodyrec {
namespace {

TEST(TrueBodies, EachVisiblePersonWithTheirTrackingIdAndAMaskOfTheirBox) {
  SynthOptions o;
  o.people = 2;
  o.seed = 5;
  o.frames = 60;
  Synthesizer synth(o);
  const RgbdFrame f = synth.render(30);
  ASSERT_TRUE(f.truth);
  const std::vector<TrueBody> bodies = true_bodies(synth.meta(), f);
  ASSERT_EQ(bodies.size(), 2u);
  std::vector<cv::Rect> boxes;
  for (const TrueBody& b : bodies) {
    const PersonTruth& p = f.truth->people[static_cast<size_t>(b.person)];
    EXPECT_EQ(b.track, p.tracking_id);
    ASSERT_EQ(b.mask.size(), b.box.size());
    ASSERT_EQ(b.mask.type(), CV_8U);
    EXPECT_GE(cv::countNonZero(b.mask), 1500);
    // The box is the mask's own: every border row and column has some of it.
    EXPECT_GT(cv::countNonZero(b.mask.row(0)), 0);
    EXPECT_GT(cv::countNonZero(b.mask.col(b.mask.cols - 1)), 0);
    boxes.push_back(b.box);
  }
  EXPECT_NE(bodies[0].person, bodies[1].person);
  // Scoring those boxes gives each its own person back.
  const BoxTruth t = truth_for_boxes(synth.meta(), f, boxes);
  EXPECT_EQ(t.visible, 2);
  EXPECT_EQ(t.person, (std::vector<int>{bodies[0].person, bodies[1].person}));
  // A frame without truth gives nobody.
  RgbdFrame bare = f;
  bare.truth.reset();
  EXPECT_TRUE(true_bodies(synth.meta(), bare).empty());
  // Nobody is that large.
  EXPECT_TRUE(true_bodies(synth.meta(), f, 10000000).empty());
}

TEST(ListedDetector, FindsWhatItWasLastToldWhateverTheFrame) {
  ListedDetector d;
  const cv::Mat frame(100, 100, CV_8UC3, cv::Scalar(0, 0, 0));
  EXPECT_TRUE(d.detect(frame).empty());
  d.set({cv::Rect(10, 20, 30, 60), cv::Rect(50, 5, 20, 40)});
  const std::vector<Detection> found = d.detect(frame);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_DOUBLE_EQ(found[1].box.x, 50);
  EXPECT_DOUBLE_EQ(found[1].box.y, 5);
  EXPECT_DOUBLE_EQ(found[1].box.width, 20);
  EXPECT_DOUBLE_EQ(found[1].box.height, 40);
  EXPECT_DOUBLE_EQ(found[0].score, 1.0);
  EXPECT_EQ(d.detect(frame).size(), 2u);  // until told otherwise
  d.set({});
  EXPECT_TRUE(d.detect(frame).empty());
}

}  // namespace
}  // namespace bodyrec
