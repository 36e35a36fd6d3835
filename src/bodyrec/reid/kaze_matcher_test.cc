#include "bodyrec/reid/kaze_matcher.h"

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// A textured person-sized image: random blobs and lines, so KAZE finds distinctive keypoints.
cv::Mat textured(int seed, cv::Size size = {96, 256}) {
  cv::RNG rng(static_cast<uint64_t>(seed));
  cv::Mat image(size, CV_8UC3, cv::Scalar(128, 128, 128));
  for (int i = 0; i < 60; ++i) {
    const cv::Point c(rng.uniform(0, size.width), rng.uniform(0, size.height));
    const cv::Scalar colour(rng.uniform(0, 256), rng.uniform(0, 256), rng.uniform(0, 256));
    if (i % 2) cv::circle(image, c, rng.uniform(3, 12), colour, cv::FILLED);
    else cv::line(image, c, {c.x + rng.uniform(-20, 20), c.y + rng.uniform(-20, 20)}, colour, 2);
  }
  return image;
}

TEST(KazeScore, ImageAgainstItselfKeepsNearlyEveryDescriptor) {
  const cv::Mat d = kaze_descriptors({textured(1), {}});
  ASSERT_GE(d.rows, 20);
  const int score = kaze_score(d, d);
  EXPECT_EQ(score % 2, 0);          // 2 x matches kept
  EXPECT_LE(score, 2 * d.rows);     // at most every probe descriptor
  EXPECT_GE(score, 2 * d.rows * 9 / 10);  // exact self-matches have ratio 0 (approximate k-d search may miss a few)
  EXPECT_GT(score, kKazeThreshold);
}

TEST(KazeScore, ShiftedCopyMatchesAndUnrelatedImageDoesNot) {
  const cv::Mat base = textured(2);
  cv::Mat shifted;
  const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, 7, 0, 1, 5);
  cv::warpAffine(base, shifted, m, base.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  const cv::Mat a = kaze_descriptors({base, {}}), b = kaze_descriptors({shifted, {}});
  const cv::Mat c = kaze_descriptors({textured(99), {}});
  const int same = kaze_score(b, a), other = kaze_score(c, a);
  EXPECT_GT(same, kKazeThreshold);
  EXPECT_GT(same, 2 * b.rows / 2);  // most of the shifted copy's descriptors find their original
  EXPECT_LT(other, same / 3);
}

TEST(KazeScore, RepeatedCallsGiveTheSameScoreSoNoMatchesAccumulate) {
  // If knnMatch appended to a reused vector, the second call would count the first call's matches too.
  const cv::Mat a = kaze_descriptors({textured(3), {}}), b = kaze_descriptors({textured(3), {}});
  const int first = kaze_score(a, b);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(kaze_score(a, b), first);
  EXPECT_LE(first, 2 * a.rows);
}

TEST(KazeScore, TooFewDescriptorsScoreZero) {
  const cv::Mat d = kaze_descriptors({textured(4), {}});
  EXPECT_EQ(kaze_score(cv::Mat(0, 64, CV_32F), d), 0);
  EXPECT_EQ(kaze_score(d, d.rowRange(0, 1)), 0);  // no second neighbour
  const cv::Mat flat(128, 48, CV_8UC3, cv::Scalar(90, 90, 90));
  EXPECT_EQ(kaze_descriptors({flat, {}}).rows, 0);
}

TEST(KazeScore, MaskLimitsKeypointsToTheBody) {
  const cv::Mat image = textured(5);
  cv::Mat mask = cv::Mat::zeros(image.size(), CV_8U);
  mask(cv::Rect(0, 0, image.cols, image.rows / 2)).setTo(255);
  EXPECT_LT(kaze_descriptors({image, mask}).rows, kaze_descriptors({image, {}}).rows);
}

TEST(KazeScore, DescriptorBlobRoundTripsAndRejectsBrokenBlobs) {
  const cv::Mat d = kaze_descriptors({textured(6), {}});
  const cv::Mat back = unpack_descriptors(pack_descriptors(d));
  EXPECT_EQ(cv::norm(back, d, cv::NORM_INF), 0.0);
  EXPECT_THROW(unpack_descriptors({}), InputError);
  EXPECT_THROW(unpack_descriptors({2, 64, 1.0f}), InputError);
}

}  // namespace
}  // namespace bodyrec
