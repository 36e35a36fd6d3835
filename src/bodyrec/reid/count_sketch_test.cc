#include "bodyrec/reid/count_sketch.h"

#include <cmath>
#include <numeric>

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

double dot(const std::vector<float>& a, const std::vector<float>& b) {
  return std::inner_product(a.begin(), a.end(), b.begin(), 0.0);
}

TEST(CountSketch, EachInputLandsInOneOutputWithASign) {
  const CountSketch s(1000, 64, 7);
  EXPECT_EQ(s.input_length(), 1000);
  EXPECT_EQ(s.output_length(), 64);
  double total = 0;
  for (int i = 0; i < 1000; ++i) {
    std::vector<float> unit(1000, 0.0f);
    unit[static_cast<size_t>(i)] = 1.0f;
    const std::vector<float> out = s.apply(unit);
    int nonzero = 0;
    for (float v : out) nonzero += v != 0;
    ASSERT_EQ(nonzero, 1) << i;
    for (float v : out) total += std::abs(v);
    EXPECT_EQ(dot(out, out), 1.0);  // norm kept for a single input
  }
  EXPECT_EQ(total, 1000.0);
}

// The map is a fixed function of (seed, lengths): two objects agree, another seed differs. The value
// pinned here changes only if the hash does, which would silently void every model trained on sketches.
TEST(CountSketch, IsAFixedFunctionOfTheSeed) {
  std::vector<float> x(500);
  for (size_t i = 0; i < x.size(); ++i) x[i] = static_cast<float>(std::sin(0.1 * static_cast<double>(i)));
  const std::vector<float> a = CountSketch(500, 50, 3).apply(x), b = CountSketch(500, 50, 3).apply(x);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, CountSketch(500, 50, 4).apply(x));
  EXPECT_NEAR(a[0], -1.038344, 1e-5);
}

// Inner products are kept on average: over many random vectors the mean error is near 0 and each
// error stays within a few 1/sqrt(k) of the norms' product.
TEST(CountSketch, KeepsInnerProductsWithinItsExpectedError) {
  const int n = 4000, k = 400;
  const CountSketch s(n, k, 11);
  uint64_t state = 1;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<float>(static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5);
  };
  double mean_error = 0, worst = 0;
  const int trials = 200;
  for (int t = 0; t < trials; ++t) {
    std::vector<float> x(n), y(n);
    for (int i = 0; i < n; ++i) x[static_cast<size_t>(i)] = next(), y[static_cast<size_t>(i)] = next();
    const double scale = std::sqrt(dot(x, x) * dot(y, y));
    const double error = (dot(s.apply(x), s.apply(y)) - dot(x, y)) / scale;
    mean_error += error / trials;
    worst = std::max(worst, std::abs(error));
  }
  EXPECT_LT(std::abs(mean_error), 0.02);
  EXPECT_LT(worst, 4.0 / std::sqrt(k));
}

}  // namespace
}  // namespace bodyrec
