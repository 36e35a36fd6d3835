#include "bodyrec/eval/detection_metrics.h"

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

LabelledBox truth(int frame, Box box, bool ignore = false) {
  LabelledBox b;
  b.frame = frame;
  b.box = box;
  b.ignore = ignore;
  return b;
}

TEST(DetectionEvaluator, HandComputedAveragePrecision) {
  DetectionEvaluator e(0.5);
  // Frame 0: two people; one found (0.9), one false alarm elsewhere (0.8). Frame 1: one person found (0.7).
  e.add_frame({{Box(0, 0, 10, 20), 0.9}, {Box(100, 100, 10, 20), 0.8}},
              {truth(0, Box(0, 0, 10, 20)), truth(0, Box(50, 0, 10, 20))});
  e.add_frame({{Box(1, 0, 10, 20), 0.7}}, {truth(1, Box(0, 0, 10, 20))});
  const DetectionScores s = e.scores();
  // Ranked: TP, FP, TP -> precision 1, 1/2, 2/3 at recall 1/3, 1/3, 2/3; envelope 1, 2/3, 2/3.
  // AP = 1/3 * 1 + 0 * 2/3 + 1/3 * 2/3 = 5/9.
  EXPECT_NEAR(s.ap, 5.0 / 9.0, 1e-12);
  EXPECT_NEAR(s.precision, 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(s.recall, 2.0 / 3.0, 1e-12);
  EXPECT_EQ(s.true_positives, 2);
  EXPECT_EQ(s.false_positives, 1);
  EXPECT_EQ(s.ground_truth, 3);
  EXPECT_EQ(s.frames, 2);
}

TEST(DetectionEvaluator, DuplicateDetectionIsFalsePositiveAndBelowThresholdMisses) {
  DetectionEvaluator e(0.5);
  // IoU of Box(5,0,10,20) with Box(0,0,10,20) is 100/300 < 0.5: a miss and a false positive.
  e.add_frame({{Box(0, 0, 10, 20), 0.9}, {Box(0, 1, 10, 20), 0.95}, {Box(5, 0, 10, 20), 0.3}},
              {truth(0, Box(0, 0, 10, 20))});
  const DetectionScores s = e.scores();
  EXPECT_EQ(s.true_positives, 1);  // the higher-scoring of the two overlapping boxes takes the person
  EXPECT_EQ(s.false_positives, 2);
  EXPECT_NEAR(s.ap, 1.0, 1e-12);  // the first-ranked detection is the hit: full recall at precision 1
}

TEST(DetectionEvaluator, IgnoredTruthNeitherHitNorMiss) {
  DetectionEvaluator e(0.5);
  e.add_frame({{Box(0, 0, 10, 20), 0.9}}, {truth(0, Box(0, 0, 10, 20), true), truth(0, Box(50, 0, 10, 20))});
  const DetectionScores s = e.scores();
  EXPECT_EQ(s.detections, 0);
  EXPECT_EQ(s.ground_truth, 1);
  EXPECT_DOUBLE_EQ(s.ap, 0.0);
}

TEST(DetectionEvaluator, NoTruthOrNoDetections) {
  DetectionEvaluator e;
  EXPECT_DOUBLE_EQ(e.scores().ap, 0.0);
  e.add_frame({}, {truth(0, Box(0, 0, 5, 5))});
  EXPECT_DOUBLE_EQ(e.scores().recall, 0.0);
  EXPECT_DOUBLE_EQ(e.scores().precision, 0.0);
}

TEST(DetectionEvaluator, BootstrapIntervalResamplesFrames) {
  DetectionEvaluator none;
  EXPECT_EQ(none.ap_interval(100), std::make_pair(0.0, 0.0));
  // Every frame perfect: every draw has AP 1.
  DetectionEvaluator perfect;
  for (int f = 0; f < 5; ++f) perfect.add_frame({{Box(0, 0, 10, 20), 0.9}}, {truth(f, Box(0, 0, 10, 20))});
  EXPECT_EQ(perfect.ap_interval(200), std::make_pair(1.0, 1.0));
  // Ten frames, half found by a confident hit, half missed with a confident false alarm: AP 0.5 for the whole
  // set, and the draws spread around it. A fixed seed gives the same interval.
  DetectionEvaluator mixed;
  for (int f = 0; f < 10; ++f) {
    const Box person(0, 0, 10, 20);
    mixed.add_frame({{f % 2 ? Box(50, 0, 10, 20) : person, f % 2 ? 0.9 : 0.8}}, {truth(f, person)});
  }
  EXPECT_NEAR(mixed.scores().ap, 0.5 * 0.5, 1e-12);  // recall 0.5, reached at precision 0.5
  const auto interval = mixed.ap_interval(1000);
  EXPECT_LT(interval.first, 0.2);
  EXPECT_GT(interval.second, 0.3);
  EXPECT_LE(interval.first, interval.second);
  EXPECT_EQ(mixed.ap_interval(1000), interval);
  const auto narrow = mixed.ap_interval(1000, 0.5);
  EXPECT_GE(narrow.first, interval.first);
  EXPECT_LE(narrow.second, interval.second);
}

TEST(AveragePrecision, PerfectRankingIsOneAndWorstRankingIsLow) {
  EXPECT_DOUBLE_EQ(average_precision({{0.9, true}, {0.8, true}, {0.1, false}}, 2), 1.0);
  // FP first: precision 0, 1/2, 2/3 at recall 0, 1/2, 1 -> envelope 2/3 everywhere -> AP 2/3.
  EXPECT_NEAR(average_precision({{0.9, false}, {0.8, true}, {0.7, true}}, 2), 2.0 / 3.0, 1e-12);
}

}  // namespace
}  // namespace bodyrec
