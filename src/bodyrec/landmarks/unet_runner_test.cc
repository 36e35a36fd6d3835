#include "bodyrec/landmarks/unet_runner.h"

#include <stdexcept>
#include <thread>

#include <omp.h>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "test_support.h"

namespace bodyrec {
namespace {

// The mask network's 15 convolutions (8 channels at full resolution), all weights and biases zero.
std::vector<ConvWeights> zero_unet() {
  const int shape[15][3] = {{8, 3, 3},   {8, 8, 3},   {16, 8, 3},  {16, 16, 3}, {32, 16, 3},
                            {32, 32, 3}, {32, 32, 3}, {32, 32, 3}, {16, 64, 3}, {16, 16, 3},
                            {8, 32, 3},  {8, 8, 3},   {8, 16, 3},  {8, 8, 3},   {1, 8, 1}};
  std::vector<ConvWeights> convs;
  for (const auto& s : shape) {
    ConvWeights c;
    c.filters = s[0];
    c.inputs = s[1];
    c.size = s[2];
    c.weights.assign(static_cast<size_t>(c.filters) * c.inputs * c.size * c.size, 0.f);
    c.biases.assign(static_cast<size_t>(c.filters), 0.f);
    convs.push_back(std::move(c));
  }
  return convs;
}

// Output channel `out` of `c` copies input channel `in` (the filter's centre tap).
void pass(ConvWeights& c, int out, int in) {
  const int centre = c.size / 2;
  c.weights[((static_cast<size_t>(out) * c.inputs + in) * c.size + centre) * c.size + centre] = 1.f;
}

TEST(UnetRunner, SkipPathAtFullResolutionCarriesTheNormalisedRedChannel) {
  // Input channel 0 is red ((v - 122.782) / 256); +1 keeps it above the ReLUs; it reaches the output only
  // through the first skip connection (the first channels of the last join), where the last 1x1 takes 1 off.
  std::vector<ConvWeights> convs = zero_unet();
  pass(convs[0], 0, 0);
  convs[0].biases[0] = 1.f;
  pass(convs[1], 0, 0);
  pass(convs[12], 0, 0);
  pass(convs[13], 0, 0);
  pass(convs[14], 0, 0);
  convs[14].biases[0] = -1.f;
  UnetRunner runner(convs, cv::Size(16, 24));
  cv::Mat crop(24, 16, CV_8UC3);
  cv::randu(crop, 0, 256);
  const cv::Mat logits = runner.forward(crop);
  ASSERT_EQ(logits.size(), cv::Size(16, 24));
  ASSERT_EQ(logits.type(), CV_32F);
  for (int y = 0; y < crop.rows; ++y)
    for (int x = 0; x < crop.cols; ++x)
      ASSERT_NEAR(logits.at<float>(y, x), (crop.at<cv::Vec3b>(y, x)[2] - 122.782f) / 256.f, 1e-5) << y << "," << x;
}

TEST(UnetRunner, BottomPathIsPooledAndUpsampledWithAlignedCorners) {
  // Green through the encoder's pools to the bottom (3x2 cells for a 24x16 crop), then up through the
  // upsampled (second) half of each join. With a crop constant per 8x8 cell, every pool keeps the cell's
  // value; the three upsamplings interpolate bilinearly with the corners aligned, so the output's corner
  // pixels are the corner cells' values exactly.
  std::vector<ConvWeights> convs = zero_unet();
  pass(convs[0], 0, 1);
  convs[0].biases[0] = 1.f;
  for (int i : {1, 2, 3, 4, 5, 6, 7, 9, 11, 13}) pass(convs[static_cast<size_t>(i)], 0, 0);
  pass(convs[8], 0, 32);   // [skip 32, up 32]
  pass(convs[10], 0, 16);  // [skip 16, up 16]
  pass(convs[12], 0, 8);   // [skip 8, up 8]
  pass(convs[14], 0, 0);
  convs[14].biases[0] = -1.f;
  UnetRunner runner(convs, cv::Size(16, 24));
  cv::Mat crop(24, 16, CV_8UC3, cv::Scalar(0, 0, 0));
  const int green[3][2] = {{10, 200}, {60, 90}, {250, 30}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 2; ++c) crop(cv::Rect(8 * c, 8 * r, 8, 8)).setTo(cv::Scalar(0, green[r][c], 0));
  const cv::Mat logits = runner.forward(crop);
  const auto value = [](int g) { return (g - 117.001f) / 256.f; };
  EXPECT_NEAR(logits.at<float>(0, 0), value(10), 1e-5);
  EXPECT_NEAR(logits.at<float>(0, 15), value(200), 1e-5);
  EXPECT_NEAR(logits.at<float>(23, 0), value(250), 1e-5);
  EXPECT_NEAR(logits.at<float>(23, 15), value(30), 1e-5);
  // Between the corners the values are interpolated: down the left column, from 10 through 60 to 250.
  for (int y = 1; y < 24; ++y) EXPECT_GE(logits.at<float>(y, 0), logits.at<float>(y - 1, 0) - 1e-6f) << y;
}

TEST(UnetRunner, RejectsAnotherLayoutAndWrongCrops) {
  std::vector<ConvWeights> convs = zero_unet();
  EXPECT_THROW(UnetRunner(std::vector<ConvWeights>(convs.begin(), convs.end() - 1), cv::Size(16, 24)),
               std::invalid_argument);
  EXPECT_THROW(UnetRunner(convs, cv::Size(12, 24)), std::invalid_argument);
  std::vector<ConvWeights> mismatched = zero_unet();
  mismatched[2].inputs = 4;  // after 8 channels
  mismatched[2].weights.resize(16 * 4 * 9);
  EXPECT_THROW(UnetRunner(mismatched, cv::Size(16, 24)), std::invalid_argument);
  UnetRunner runner(convs, cv::Size(16, 24));
  EXPECT_THROW(runner.forward(cv::Mat(24, 16, CV_8UC1, cv::Scalar(0))), std::invalid_argument);
  EXPECT_THROW(runner.forward(cv::Mat(16, 24, CV_8UC3, cv::Scalar(0, 0, 0))), std::invalid_argument);
  EXPECT_EQ(runner.forward(cv::Mat(24, 16, CV_8UC3, cv::Scalar(0, 0, 0))).at<float>(5, 5), 0.f);
}

TEST(UnetRunner, LeavesTheCallersOpenMpSettingAsItWas) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(3);
  UnetRunner runner(zero_unet(), cv::Size(16, 24));
  runner.forward(cv::Mat(24, 16, CV_8UC3, cv::Scalar(0, 0, 0)));
  EXPECT_EQ(omp_get_max_threads(), 3);
  omp_set_num_threads(before);
}

// oneDNN's convolutions fix their thread count when they are made: a runner made while OpenMP may use
// several threads would start a team at every call. A new thread has its own OpenMP pool, so any team
// the runner starts on it adds threads that stay until it ends.
TEST(UnetRunner, StartsNoOpenMpThreadsWhateverTheCallersSetting) {
  size_t before = 0, after = 0;
  std::thread caller([&] {
    omp_set_num_threads(4);
    before = testing::process_threads();
    UnetRunner runner(zero_unet(), cv::Size(16, 24));
    runner.forward(cv::Mat(24, 16, CV_8UC3, cv::Scalar(0, 0, 0)));
    after = testing::process_threads();
  });
  caller.join();
  EXPECT_GT(before, 0u);
  EXPECT_LE(after, before);  // not EQ: an earlier test's pool threads may still be ending
}

}  // namespace
}  // namespace bodyrec
