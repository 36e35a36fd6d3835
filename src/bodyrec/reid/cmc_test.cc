#include "bodyrec/reid/cmc.h"

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

TEST(RankingScores, HandComputedCmcAndMapWithoutTies) {
  // 3 probes (ids 1, 2, 3) x 4 gallery images (ids 1, 2, 3, 9 = distractor).
  const cv::Mat s = (cv::Mat_<double>(3, 4) << 0.9, 0.1, 0.2, 0.3,   // probe 1: correct first -> rank 1
                     0.8, 0.5, 0.7, 0.1,                              // probe 2: 0.8, 0.7 above -> rank 3
                     0.1, 0.2, 0.6, 0.9);                             // probe 3: distractor above -> rank 2
  const RankingScores r = ranking_scores(s, {1, 2, 3}, {1, 2, 3, 9}, 4);
  EXPECT_EQ(r.probes, 3);
  EXPECT_DOUBLE_EQ(r.cmc[0], 1.0 / 3);
  EXPECT_DOUBLE_EQ(r.cmc[1], 2.0 / 3);
  EXPECT_DOUBLE_EQ(r.cmc[2], 1.0);
  EXPECT_DOUBLE_EQ(r.cmc[3], 1.0);
  EXPECT_DOUBLE_EQ(r.map, (1.0 + 1.0 / 3 + 1.0 / 2) / 3);  // one correct image each: AP = 1 / rank
}

TEST(RankingScores, SeveralCorrectImagesGiveStandardAp) {
  // Probe id 5; gallery ids 5, 7, 5, 7 with similarities ranking them 7, 5, 7, 5 -> correct at 2 and 4.
  const cv::Mat s = (cv::Mat_<double>(1, 4) << 0.8, 0.9, 0.6, 0.7);
  const RankingScores r = ranking_scores(s, {5}, {5, 7, 5, 7}, 3);
  EXPECT_DOUBLE_EQ(r.cmc[0], 0.0);
  EXPECT_DOUBLE_EQ(r.cmc[1], 1.0);
  EXPECT_DOUBLE_EQ(r.map, (1.0 / 2 + 2.0 / 4) / 2);
}

TEST(RankingScores, TiesCountAsTheirRandomOrderExpectation) {
  // All four tied: the single correct image is at rank 1..4 with probability 1/4 each.
  const cv::Mat s = cv::Mat::zeros(1, 4, CV_64F);
  const RankingScores r = ranking_scores(s, {1}, {1, 2, 3, 4}, 5);
  EXPECT_DOUBLE_EQ(r.cmc[0], 0.25);
  EXPECT_DOUBLE_EQ(r.cmc[1], 0.5);
  EXPECT_DOUBLE_EQ(r.cmc[3], 1.0);
  EXPECT_DOUBLE_EQ(r.cmc[4], 1.0);
  EXPECT_DOUBLE_EQ(r.map, 1.0 / 2.5);  // expected position (4 + 1) / 2
  // One wrong image strictly above, then a tie of the correct one with one wrong one.
  const cv::Mat t = (cv::Mat_<double>(1, 3) << 0.5, 0.5, 0.9);
  const RankingScores q = ranking_scores(t, {1}, {1, 2, 3}, 3);
  EXPECT_DOUBLE_EQ(q.cmc[0], 0.0);
  EXPECT_DOUBLE_EQ(q.cmc[1], 0.5);
  EXPECT_DOUBLE_EQ(q.cmc[2], 1.0);
  // Two correct among four tied: P(first correct at 1) = 1/2, within 2 = 1 - (2/4)(1/3) = 5/6.
  const RankingScores two = ranking_scores(cv::Mat::zeros(1, 4, CV_64F), {1}, {1, 1, 2, 3}, 3);
  EXPECT_DOUBLE_EQ(two.cmc[0], 0.5);
  EXPECT_DOUBLE_EQ(two.cmc[1], 5.0 / 6);
  EXPECT_DOUBLE_EQ(two.cmc[2], 1.0);
}

TEST(RankingScores, ProbesWithoutACorrectImageAreNotScored) {
  const cv::Mat s = (cv::Mat_<double>(2, 2) << 0.9, 0.1, 0.9, 0.1);
  const RankingScores r = ranking_scores(s, {1, 4}, {1, 2}, 2);
  EXPECT_EQ(r.probes, 1);
  EXPECT_DOUBLE_EQ(r.cmc[0], 1.0);
  EXPECT_DOUBLE_EQ(r.map, 1.0);
}

}  // namespace
}  // namespace bodyrec
