// Pair features on hand-made trajectories with values computed by hand.
#include "bodyrec/groups/pair_features.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace bodyrec {
namespace {

constexpr double kAll = std::numeric_limits<double>::infinity();

// n samples, 0.4 s apart, starting at `start`, moving with `velocity` from `origin`.
PersonHistory walk(cv::Point2d origin, cv::Point2d velocity, int n, int first_step = 1) {
  PersonHistory h;
  for (int k = 0; k < n; ++k) {
    const double t = 0.4 * (first_step - 1 + k);
    h.add(first_step + k, t, origin + velocity * t, 0.4);
  }
  return h;
}

TEST(PersonHistory, VelocityFromDisplacementOverTheSpan) {
  const PersonHistory h = walk({0, 0}, {1.5, -0.5}, 5);
  ASSERT_EQ(h.samples().size(), 5u);
  EXPECT_FALSE(h.samples()[0].has_velocity);  // nothing earlier
  for (size_t k = 1; k < 5; ++k) {
    EXPECT_TRUE(h.samples()[k].has_velocity);
    EXPECT_NEAR(h.samples()[k].velocity.x, 1.5, 1e-9);
    EXPECT_NEAR(h.samples()[k].velocity.y, -0.5, 1e-9);
  }
  EXPECT_DOUBLE_EQ(h.first_seen(), 0.0);
  EXPECT_DOUBLE_EQ(h.last_seen(), 1.6);
}

TEST(PairFeatures, SideBySideWalkers) {
  const PersonHistory a = walk({0, 0}, {1.5, 0}, 11), b = walk({0, 1}, {1.5, 0}, 11);
  const auto f = pair_features(a, b, kAll, kAll);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->samples, 10);  // the first sample has no velocity
  EXPECT_NEAR(f->median_distance, 1.0, 1e-9);
  EXPECT_NEAR(f->median_speed_difference, 0.0, 1e-9);
  const auto& v = f->values;
  EXPECT_NEAR(v[0], std::log(1.1), 1e-9);  // log_median_distance
  EXPECT_NEAR(v[2], 0.0, 1e-9);            // distance_std
  EXPECT_NEAR(v[3], 0.0, 1e-9);            // median_velocity_difference
  EXPECT_NEAR(v[6], std::log(1.6), 1e-9);  // log_mean_speed
  EXPECT_NEAR(v[7], 1.0, 1e-9);            // heading_agreement
  EXPECT_NEAR(v[8], 1.0, 1e-9);            // moving_fraction
  EXPECT_NEAR(v[9], 1.0 / 1.1, 1e-9);      // side_by_side
  EXPECT_NEAR(v[10], std::log(3.6 + 0.4), 1e-9);  // samples 2..11 span 3.6 s
  EXPECT_NEAR(v[11], 0.0, 1e-9);                  // distance_change_rate
  EXPECT_NEAR(v[12], std::log(1.1), 1e-9);        // moving x log distance
  EXPECT_NEAR(v[14], std::log(1.1) / 1.1, 1e-9);  // side by side x log distance
}

TEST(PairFeatures, OneBehindTheOtherAndOpposingWalkers) {
  const PersonHistory a = walk({0, 0}, {1.5, 0}, 6), behind = walk({-1.2, 0}, {1.5, 0}, 6);
  auto f = pair_features(a, behind, kAll, kAll);
  ASSERT_TRUE(f);
  EXPECT_NEAR(f->values[9], 0.0, 1e-9);
  EXPECT_NEAR(f->median_distance, 1.2, 1e-9);
  const PersonHistory opposite = walk({8, 0.5}, {-1.5, 0}, 6);
  f = pair_features(a, opposite, kAll, kAll);
  ASSERT_TRUE(f);
  EXPECT_NEAR(f->values[7], -1.0, 1e-9);  // heading_agreement
  EXPECT_NEAR(f->values[3], 3.0, 1e-9);   // |va - vb|
  EXPECT_NEAR(f->median_speed_difference, 0.0, 1e-9);
}

TEST(PairFeatures, OnlyCommonStepsInsideTheWindowCount) {
  const PersonHistory a = walk({0, 0}, {1, 0}, 20), late = walk({0, 1}, {1, 0}, 10, 11);
  auto f = pair_features(a, late, kAll, kAll);
  ASSERT_TRUE(f);
  EXPECT_EQ(f->samples, 9);  // steps 12..20
  EXPECT_NEAR(f->values[10], std::log(3.2 + 0.4), 1e-9);  // 8 intervals of 0.4 s
  f = pair_features(a, late, 0.4 * 19, 1.2);                // t in [6.4, 7.6]: steps 17..20
  ASSERT_TRUE(f);
  EXPECT_EQ(f->samples, 4);
  EXPECT_FALSE(pair_features(a, late, 0.4 * 19, 0.3));  // one common sample is not enough
  EXPECT_FALSE(pair_features(a, walk({0, 0}, {1, 0}, 3, 30), kAll, kAll));  // never together
}

TEST(PairFeatures, DroppingOldSamplesDoesNotChangeWindowedFeatures) {
  PersonHistory a, b, a_full, b_full;
  for (int k = 0; k < 60; ++k) {
    const double t = 0.15 * k;  // ~7 fps, a wobbling pair
    const cv::Point2d pa(1.2 * t, 0.2 * std::sin(t)), pb(1.2 * t + 0.3 * std::cos(2 * t), 0.9);
    for (PersonHistory* h : {&a, &a_full}) h->add(k + 1, t, pa, 0.4);
    for (PersonHistory* h : {&b, &b_full}) h->add(k + 1, t, pb, 0.4);
    a.drop_before(t - 3.0);
    b.drop_before(t - 3.0);
    const auto trimmed = pair_features(a, b, t, 3.0), full = pair_features(a_full, b_full, t, 3.0);
    ASSERT_EQ(trimmed.has_value(), full.has_value());
    if (!trimmed) continue;
    for (int i = 0; i < kPairFeatureCount; ++i) EXPECT_DOUBLE_EQ(trimmed->values[i], full->values[i]) << k;
  }
  EXPECT_LE(a.samples().size(), 25u);  // 3 s window + 0.4 s span at 0.15 s, not all 60
}

}  // namespace
}  // namespace bodyrec
