#include "bodyrec/detection/foreground_detector.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// A static textured background (640x360) with upright "people" (solid rectangles) drawn on it.
cv::Mat scene(const std::vector<cv::Rect>& people) {
  cv::Mat img(360, 640, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(img, cv::RNG::UNIFORM, cv::Scalar(90, 90, 90), cv::Scalar(150, 150, 150));
  cv::GaussianBlur(img, img, {5, 5}, 2);
  const cv::Scalar colours[] = {{40, 40, 200}, {200, 60, 30}, {30, 180, 30}};
  for (size_t i = 0; i < people.size(); ++i) {
    // A body below a narrower head (the top fifth).
    const cv::Rect& p = people[i];
    const int head = p.height / 5;
    cv::rectangle(img, cv::Rect(p.x, p.y + head, p.width, p.height - head), colours[i % 3], cv::FILLED);
    cv::rectangle(img, cv::Rect(p.x + p.width * 3 / 10, p.y, p.width * 4 / 10, head), cv::Scalar(60, 120, 200),
                  cv::FILLED);
  }
  return img;
}

double best_iou(const std::vector<Detection>& found, const cv::Rect& r) {
  double best = 0;
  for (const Detection& d : found) best = std::max(best, iou(d.box, Box(r)));
  return best;
}

TEST(ForegroundPeopleDetector, FindsAWalkerAfterWarmUp) {
  ForegroundPeopleDetector people;
  std::vector<Detection> found;
  cv::Rect walker;
  for (int i = 0; i < 40; ++i) {
    walker = cv::Rect(40 + 8 * i, 150, 50, 150);
    found = people.detect(scene({walker}));
    if (i < 10) {
      EXPECT_TRUE(found.empty()) << "warm-up frame " << i;
    }
  }
  ASSERT_EQ(found.size(), 1u);
  EXPECT_GT(iou(found[0].box, Box(walker)), 0.8);
  EXPECT_GT(found[0].score, 0.85);  // a solid body fills most of its box
  // The mask inside the walker's box is foreground; beside it, background.
  const cv::Mat inside = people.model().mask_in(walker);
  ASSERT_EQ(inside.size(), walker.size());
  EXPECT_GT(cv::countNonZero(inside), walker.area() * 3 / 4);
  EXPECT_EQ(cv::countNonZero(people.model().mask_in({walker.x + 100, 150, 50, 150})), 0);
}

TEST(ForegroundPeopleDetector, SplitsPeopleWalkingSideBySide) {
  ForegroundPeopleDetector people;
  std::vector<Detection> found;
  cv::Rect a, b;
  for (int i = 0; i < 40; ++i) {
    a = cv::Rect(40 + 8 * i, 150, 50, 150);
    b = cv::Rect(a.x + 50, 145, 50, 160);  // touching: one foreground component with two heads
    found = people.detect(scene({a, b}));
  }
  ASSERT_EQ(found.size(), 2u);
  EXPECT_GT(best_iou(found, a), 0.7);
  EXPECT_GT(best_iou(found, b), 0.7);
}

TEST(ForegroundPeopleDetector, StillSceneAndSmallSpecksGiveNobody) {
  ForegroundPeopleDetector people;
  for (int i = 0; i < 30; ++i) {
    // A 10x10 speck moving about: far below a person's height.
    const std::vector<Detection> found = people.detect(scene({{50 + 5 * i, 50, 10, 10}}));
    EXPECT_TRUE(found.empty()) << i;
  }
}

TEST(ForegroundPeopleDetector, SplitCutsAtTheThinnestColumn) {
  cv::Mat c = cv::Mat::zeros(100, 200, CV_8U);
  c(cv::Rect(10, 10, 40, 80)).setTo(255);
  c(cv::Rect(50, 40, 6, 10)).setTo(255);  // a thin bridge
  c(cv::Rect(56, 5, 44, 90)).setTo(255);
  ForegroundOptions o;
  o.person_aspect = 0.45;  // 90 / (0.45 x 90): two parts
  const auto parts = split_component(c, {10, 5, 90, 90}, o);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].x, 10);
  EXPECT_EQ(parts[1].br().x, 100);
  EXPECT_NEAR(parts[0].br().x, 53, 4);
  EXPECT_EQ(parts[1].y, 5);   // each part's own rows
  EXPECT_EQ(parts[0].y, 10);
  // A person-shaped component stays whole.
  EXPECT_EQ(split_component(c, {10, 10, 40, 80}, o).size(), 1u);
  // As wide as two people: two heads make two, one head one.
  cv::Mat two = cv::Mat::zeros(100, 100, CV_8U);
  two(cv::Rect(10, 20, 60, 80)).setTo(255);
  two(cv::Rect(15, 0, 15, 20)).setTo(255);
  two(cv::Rect(50, 2, 15, 18)).setTo(255);
  const auto heads = split_component(two, {10, 0, 60, 100}, o);
  ASSERT_EQ(heads.size(), 2u);
  EXPECT_EQ(heads[0].x, 10);
  EXPECT_EQ(heads[0].br().x, 40);  // the middle of the gap between the heads (30..50)
  EXPECT_EQ(heads[1].y, 2);
  two(cv::Rect(50, 2, 15, 18)).setTo(0);
  EXPECT_EQ(split_component(two, {10, 0, 60, 100}, o).size(), 1u);
}

TEST(ForegroundPeopleDetector, BadOptionsAndFramesAreRefused) {
  ForegroundOptions o;
  o.min_height = 0;
  EXPECT_THROW(ForegroundPeopleDetector{o}, UsageError);
  o = {};
  o.person_aspect = 2;
  EXPECT_THROW(ForegroundPeopleDetector{o}, UsageError);
  ForegroundPeopleDetector people;
  people.detect(scene({}));
  EXPECT_THROW(people.detect(cv::Mat(100, 100, CV_8UC3, cv::Scalar(0, 0, 0))), InputError);
  EXPECT_THROW(people.detect(cv::Mat()), InputError);
}

}  // namespace
}  // namespace bodyrec
