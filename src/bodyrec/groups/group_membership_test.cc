// The online API on hand-made trajectories at the tracker's ~7 fps, with the built-in model.
#include "bodyrec/groups/group_membership.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

using Positions = std::vector<std::pair<int, cv::Point2d>>;

// Calls `update` every 1/7 s for `seconds`, positions from `at(t)`.
void run(GroupMembership& g, double from, double seconds, const std::function<Positions(double)>& at) {
  for (double t = from; t < from + seconds; t += 1.0 / 7) g.update(t, at(t));
}

// Two friends walking east side by side 0.7 m apart, a passer-by crossing their path walking north.
Positions friends_and_passer_by(double t) {
  return {{1, {1.3 * t, 0.0}}, {2, {1.3 * t, 0.7}}, {7, {13.0, -8.0 + 1.4 * t}}};
}

TEST(GroupMembership, FriendsFormOneGroupAndThePasserByIsNotInIt) {
  GroupMembership g;
  run(g, 0, 12, friends_and_passer_by);
  EXPECT_EQ(g.groups(), (std::vector<std::vector<int>>{{1, 2}}));
  const auto of = g.group_of();
  ASSERT_EQ(of.size(), 2u);
  EXPECT_EQ(of.at(1), of.at(2));
  EXPECT_EQ(of.count(7), 0u);
  EXPECT_GT(g.pair_probability(1, 2), 0.9);
  EXPECT_LT(g.pair_probability(1, 7), 0.1);
  EXPECT_LT(g.pair_probability(2, 7), 0.1);
  EXPECT_EQ(g.pair_probability(1, 99), 0.0);  // unknown id
}

TEST(GroupMembership, TwoGroupsAtOnceGetDistinctStableIds) {
  GroupMembership g;
  const auto at = [](double t) -> Positions {
    return {{1, {1.2 * t, 0.0}},       {2, {1.2 * t, 0.6}},       // east, a couple
            {3, {20 - 1.0 * t, 6.0}},  {4, {20 - 1.0 * t, 6.7}},  {5, {20.4 - 1.0 * t, 7.4}},  // west, three
            {6, {5.0, 12.0}}};                                    // someone standing far away
  };
  run(g, 0, 6, at);
  const auto first = g.group_of();
  run(g, 6, 6, at);
  EXPECT_EQ(g.groups(), (std::vector<std::vector<int>>{{1, 2}, {3, 4, 5}}));
  const auto of = g.group_of();
  EXPECT_EQ(of.at(1), of.at(2));
  EXPECT_EQ(of.at(3), of.at(4));
  EXPECT_EQ(of.at(4), of.at(5));
  EXPECT_NE(of.at(1), of.at(3));
  EXPECT_EQ(of.count(6), 0u);
  ASSERT_EQ(first.size(), 5u);  // already grouped after 6 s, with the same ids as at the end
  EXPECT_EQ(first, of);
}

TEST(GroupMembership, PixelPositionsWithAScaleGiveTheSameGroups) {
  GroupOptions options;
  options.units_per_metre = 40;  // pixels per metre
  GroupMembership pixels(options), metres;
  run(pixels, 0, 10, [](double t) {
    Positions p = friends_and_passer_by(t);
    for (auto& [id, at] : p) at *= 40;
    return p;
  });
  run(metres, 0, 10, friends_and_passer_by);
  EXPECT_EQ(pixels.groups(), metres.groups());
  EXPECT_NEAR(pixels.pair_probability(1, 2), metres.pair_probability(1, 2), 1e-9);
}

TEST(GroupMembership, ForgetsPeopleWhoLeftAndBoundsMemory) {
  GroupOptions windowed;
  windowed.window_s = 8;
  GroupMembership g(windowed);
  run(g, 0, 10, friends_and_passer_by);
  g.forget(2);
  EXPECT_EQ(g.pair_probability(1, 2), 0.0);
  EXPECT_TRUE(g.groups().empty());
  // Person 7 stops being reported; after forget_after_s (2 s) it is gone.
  run(g, 10, 3, [](double t) { return Positions{{1, {1.3 * t, 0.0}}}; });
  EXPECT_EQ(g.people(), std::vector<int>{1});
  const auto f = g.window_features(1, 1);
  ASSERT_TRUE(f);  // a person paired with itself: only the window's samples remain
  EXPECT_LE(f->samples, 8 * 7 + 1);

  // Over the whole common time (the default), history is kept up to max_history_s.
  GroupOptions whole;
  whole.max_history_s = 30;
  GroupMembership w(whole);
  run(w, 0, 20, friends_and_passer_by);
  EXPECT_EQ(w.window_features(1, 2)->samples, 140);  // 141 updates, all but the first (no velocity yet)
  run(w, 20, 30, friends_and_passer_by);
  EXPECT_LE(w.window_features(1, 2)->samples, 30 * 7 + 1);
}

TEST(GroupMembership, WithAHalfLifeAPairThatSplitsUpLeavesItsGroup) {
  GroupOptions options;
  options.window_s = 8;  // the built-in rule per 8 s window, its votes fading with a 2 s half-life
  options.evidence_half_life_s = 2;
  GroupMembership g(options);
  // Together for 12 s, then 2 turns north while 1 walks on east.
  const auto at = [](double t) -> Positions {
    const double after = std::max(0.0, t - 12);
    return {{1, {1.3 * t, 0.0}}, {2, {1.3 * (t - after), 0.7 + 1.3 * after}}};
  };
  run(g, 0, 12, at);
  EXPECT_EQ(g.groups(), (std::vector<std::vector<int>>{{1, 2}}));
  run(g, 12, 8, at);
  EXPECT_TRUE(g.groups().empty());
  EXPECT_LT(g.pair_probability(1, 2), 0.5);
}

TEST(GroupMembership, OverTheWholeCommonTimeAPairLeavesItsGroupOnceApartLongerThanTogether) {
  GroupMembership g;  // the default: the rule on medians over all the pair's common time
  const auto at = [](double t) -> Positions {
    const double after = std::max(0.0, t - 12);
    return {{1, {1.3 * t, 0.0}}, {2, {1.3 * (t - after), 0.7 + 1.3 * after}}};
  };
  run(g, 0, 12, at);
  EXPECT_EQ(g.groups(), (std::vector<std::vector<int>>{{1, 2}}));
  run(g, 12, 8, at);  // apart for 8 s of 20: the medians still say together
  EXPECT_EQ(g.groups(), (std::vector<std::vector<int>>{{1, 2}}));
  run(g, 20, 6, at);  // apart for 14 s of 26
  EXPECT_TRUE(g.groups().empty());
  EXPECT_LT(g.pair_probability(1, 2), 0.1);
}

TEST(GroupMembership, RejectsTimeGoingBackDuplicateIdsAndBadOptions) {
  GroupMembership g;
  g.update(1.0, {{1, {0, 0}}});
  EXPECT_THROW(g.update(1.0, {{1, {0, 0}}}), UsageError);
  EXPECT_THROW(g.update(2.0, {{1, {0, 0}}, {1, {1, 0}}}), UsageError);
  GroupOptions bad;
  bad.window_s = 0;
  EXPECT_THROW(GroupMembership{bad}, UsageError);
  bad = GroupOptions{};
  bad.units_per_metre = -1;
  EXPECT_THROW(bad.check(), UsageError);
}

TEST(ClusterPairs, AverageLinkageCompletesTrianglesWithoutChainingGroups) {
  // A-B and B-C strongly together, A-C slightly apart: one group of three.
  std::map<std::pair<int, int>, double> e = {{{1, 2}, 3.0}, {{2, 3}, 3.0}, {{1, 3}, -0.5}};
  EXPECT_EQ(cluster_pairs({1, 2, 3}, e, GroupLinkage::kAverage), (std::vector<std::vector<int>>{{1, 2, 3}}));
  // Two pairs joined by one weak link and three clear "apart" links: average keeps them apart,
  // single linkage chains them.
  e = {{{1, 2}, 3.0}, {{3, 4}, 3.0}, {{2, 3}, 0.2}, {{1, 3}, -3.0}, {{1, 4}, -3.0}, {{2, 4}, -3.0}};
  EXPECT_EQ(cluster_pairs({1, 2, 3, 4, 5}, e, GroupLinkage::kAverage),
            (std::vector<std::vector<int>>{{1, 2}, {3, 4}, {5}}));
  EXPECT_EQ(cluster_pairs({1, 2, 3, 4, 5}, e, GroupLinkage::kSingle),
            (std::vector<std::vector<int>>{{1, 2, 3, 4}, {5}}));
}

}  // namespace
}  // namespace bodyrec
