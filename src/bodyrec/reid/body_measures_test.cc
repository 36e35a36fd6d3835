#include "bodyrec/reid/body_measures.h"

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

#include "box_scene.h"

namespace bodyrec {
namespace {

using testing::person;
using testing::render;
using testing::Slab;

const GroundPlane kFloor(0, 1, 0, 1);  // the box scene's floor: 1 m below the camera

std::optional<double> stature(const std::vector<Slab>& scene, std::string* why = nullptr, int label = 0) {
  cv::Mat labels;
  const cv::Mat depth = render(scene, &labels);
  return measure_stature(depth, 0.001, kinect2_depth_intrinsics(), labels, label, kFloor, {}, why);
}

TEST(Stature, TopOfTheBodyAboveTheFloor) {
  // Box people 1.62 and 1.91 m tall at 2.5 and 4 m: one depth row is 7 and 11 mm there.
  const auto a = stature(person(-0.6, 2.5, 1.62, 0) + person(0.8, 4.0, 1.91, 1));
  ASSERT_TRUE(a);
  EXPECT_NEAR(*a, 1.62, 0.015);
  const auto b = stature(person(-0.6, 2.5, 1.62, 0) + person(0.8, 4.0, 1.91, 1), nullptr, 1);
  ASSERT_TRUE(b);
  EXPECT_NEAR(*b, 1.91, 0.02);
}

TEST(Stature, RefusedWhenTheTopMayNotBeThePersons) {
  std::string why;
  // Someone nearer hides half the head: the visible top may not be the person's.
  EXPECT_FALSE(stature(person(0.0, 4.0, 1.75, 0) + std::vector<Slab>{{0.0, 0.5, 0.0, 1.9, 2.5}}, &why));
  EXPECT_EQ(why, "a nearer surface covers the body's top");
  // The head at the image's side: it may go on outside.
  EXPECT_FALSE(stature(person(-2.0, 3.0, 1.75, 0), &why));  // the head's left edge at u = 0
  EXPECT_EQ(why, "the body's head is at the image border");
  // Too close: the head is above the image.
  EXPECT_FALSE(stature(person(0.0, 0.9, 1.75, 0), &why));
  EXPECT_EQ(why, "the body's head is at the image border");
  EXPECT_FALSE(stature({{-0.1, 0.1, 0.0, 0.5, 3.0, 0}}, &why));  // a small box: 0.5 m is no stature
  EXPECT_EQ(why.rfind("implausible stature", 0), 0u) << why;
  // A person behind, not in front, does not count: a farther surface next to the head is background.
  EXPECT_TRUE(stature(person(0.0, 2.5, 1.75, 0) + std::vector<Slab>{{-0.5, 0.5, 0.0, 2.0, 3.5}}));
}

TEST(Stature, BadInputIsAnInputError) {
  const Intrinsics k = kinect2_depth_intrinsics();
  EXPECT_THROW(measure_stature(cv::Mat(10, 10, CV_16U), 0.001, k, cv::Mat(10, 10, CV_8U), 0, kFloor), InputError);
  StatureOptions o;
  o.top_rank = 0;
  EXPECT_THROW(o.check(), UsageError);
}

TEST(StatureTrack, UpperQuartileOfTheMeasurements) {
  StatureTrack t;
  EXPECT_FALSE(t.estimate());
  for (double s : {1.70, 1.80, 1.72, 1.74}) t.add(s);
  EXPECT_EQ(t.count(), 4);
  EXPECT_DOUBLE_EQ(*t.estimate(), 1.80);   // 4 values: the 4th of them sorted (index 3)
  EXPECT_DOUBLE_EQ(*t.estimate(2), 1.74);  // the last two: 1.72, 1.74
  for (double s : {1.71, 1.73, 1.75, 1.76}) t.add(s);
  EXPECT_DOUBLE_EQ(*t.estimate(), 1.76);   // 8 values sorted, index 6
  StatureTrack bounded(1, 3);
  for (double s : {2.0, 1.0, 1.1, 1.2}) bounded.add(s);
  EXPECT_EQ(bounded.count(), 4);
  EXPECT_DOUBLE_EQ(*bounded.estimate(), 1.2);  // 2.0 fell out
}

}  // namespace
}  // namespace bodyrec
