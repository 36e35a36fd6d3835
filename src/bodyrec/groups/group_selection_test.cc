// Model selection on hand-made scenes: fitting the learned rule, choosing among a grid by
// leave-one-scene-out within the training scenes only, nested leave-one-scene-out.
#include "bodyrec/groups/group_selection.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// 20 s, frames every 0.4 s: 1-2 walk east side by side `pair_distance` apart, 3-4 walk west 0.8 m
// apart, 5 walks east 2.5 m from 1 (alone), 6-7 stand 1 m apart (not a group), 8 crosses.
WalkingScene scene(const std::string& name, double pair_distance) {
  WalkingScene s;
  s.name = name;
  s.seconds_per_frame = 0.4;
  for (int f = 0; f < 50; ++f) {
    const double t = 0.4 * f;
    const cv::Point2d at[] = {{1.2 * t, 0},          {1.2 * t, pair_distance}, {30 - t, 6}, {30 - t, 6.8},
                              {1.2 * t, -2.5},       {5, 12},                   {6, 12},     {15, -10 + 1.4 * t}};
    for (int id = 1; id <= 8; ++id) {
      ObsmatRow r;
      r.frame = f;
      r.person = id;
      r.position = at[id - 1];
      s.rows.push_back(r);
    }
  }
  s.groups = {{1, 2}, {3, 4}};
  return s;
}

GroupCandidate learned_rule(GroupLinkage linkage, double moving) {
  GroupCandidate c;
  c.method = GroupMethod::kLearnedRule;
  c.linkage = linkage;
  c.features = distance_speed_features();
  c.window_s = std::numeric_limits<double>::infinity();
  c.min_moving_fraction = moving;
  return c;
}

TEST(GroupSelection, LearnedRuleTakesTheStrictestThresholdsThatFitTheTrainingScenes) {
  GroupSelection selection({scene("a", 0.6), scene("b", 1.0)});
  const FittedGroupMethod& f = selection.fit(learned_rule(GroupLinkage::kSingle, 0.5), {0, 1});
  // The first of the grid that takes 1-2 at 1.0 m and 3-4 at 0.8 m: 1.0 m, with the smallest speed limit.
  EXPECT_DOUBLE_EQ(f.max_distance_m, 1.0);
  EXPECT_DOUBLE_EQ(f.max_speed_difference, 0.05);
  ASSERT_TRUE(f.model);
  EXPECT_TRUE(f.model->rule);
  EXPECT_EQ(f.model->trained_on, (std::vector<std::string>{"a", "b"}));
  EXPECT_DOUBLE_EQ(selection.score(f, 0).f1, 1.0);
  EXPECT_EQ(describe(f),
            "learned rule 1 m / 0.05 m/s, whole common time, min-moving 0.5, velocity span 0.4 s, linkage single");
  // Standing pairs count when min-moving is 0: fitted on b, the rule then takes the pair standing 1 m apart.
  const FittedGroupMethod& all = selection.fit(learned_rule(GroupLinkage::kSingle, 0), {1});
  EXPECT_DOUBLE_EQ(all.max_distance_m, 1.0);
  const PairScores s = selection.score(all, 0);
  EXPECT_EQ(s.predicted_pairs, 3);
  EXPECT_EQ(s.true_pairs, 2);
}

TEST(GroupSelection, PlainRuleNeedsNoFitting) {
  GroupSelection selection({scene("a", 0.6)});
  GroupCandidate c;
  c.method = GroupMethod::kRule;
  c.linkage = GroupLinkage::kNone;
  const PairScores s = selection.score(selection.fit(c, {0}), 0);
  EXPECT_EQ(s.predicted_pairs, 3);  // 1-2, 3-4 and the standing 6-7
  EXPECT_NEAR(s.f1, 0.8, 1e-12);
}

TEST(GroupSelection, ChoosesByLeaveOneSceneOutWithinTheTrainingScenesOnly) {
  // In a and b the pair walks 0.6 and 1.0 m apart, in c 1.8 m: fitted on a (or b) alone, the rule misses
  // the other's pair only when its distance is larger.
  GroupSelection selection({scene("a", 0.6), scene("b", 1.0), scene("c", 1.8)});
  GroupFamily family{"two", {learned_rule(GroupLinkage::kSingle, 0), learned_rule(GroupLinkage::kSingle, 0.5)}};
  double f1 = 0;
  const GroupCandidate chosen = selection.choose(family, {0, 1}, &f1);
  EXPECT_EQ(chosen.min_moving_fraction, 0.5);  // the standing pair costs min-moving 0 precision
  EXPECT_NEAR(f1, selection.inner_f1(chosen, {0, 1}), 1e-15);
  EXPECT_NEAR(f1, 0.5 * (selection.score(selection.fit(chosen, {1}), 0).f1 +
                         selection.score(selection.fit(chosen, {0}), 1).f1),
              1e-15);
  // Nothing to choose by with one training scene: the first candidate.
  EXPECT_EQ(selection.choose(family, {0}).min_moving_fraction, 0.0);

  const NestedResult r = selection.nested_loso(family);
  ASSERT_EQ(r.folds.size(), 3u);
  EXPECT_EQ(r.folds[2].scene, "c");
  // c's pair at 1.8 m is beyond what a and b teach (<= 1.0 m): recall 1/2 there.
  EXPECT_NEAR(r.folds[2].scores.recall, 0.5, 1e-12);
  EXPECT_NEAR(r.folds[0].scores.f1, 1.0, 1e-12);
  EXPECT_NEAR(r.mean_f1, (r.folds[0].scores.f1 + r.folds[1].scores.f1 + r.folds[2].scores.f1) / 3, 1e-15);

  GroupSelection two({scene("a", 0.6), scene("b", 1.0)});
  EXPECT_THROW(two.nested_loso(family), UsageError);
  EXPECT_THROW(two.inner_f1(family.grid[0], {0}), UsageError);
}

TEST(GroupSelection, PairModelFitsAndScoresLikeTheReplay) {
  GroupSelection selection({scene("a", 0.6), scene("b", 1.0)});
  GroupCandidate c;
  c.method = GroupMethod::kPairModel;
  c.features = distance_speed_features();
  c.l2 = 1;
  c.window_s = 8;
  const FittedGroupMethod& f = selection.fit(c, {0, 1});
  ASSERT_TRUE(f.model);
  EXPECT_FALSE(f.model->rule);
  for (int i = 0; i < kPairFeatureCount; ++i) {
    if (i != 0 && i != 4) {
      EXPECT_EQ(f.model->weights[i], 0.0);
    }
  }
  EXPECT_LT(f.model->weights[0], 0);  // farther apart: less likely together
  const WalkingScene b = selection.scenes()[1];
  const GroupOptions options = options_for(f.model);
  EXPECT_DOUBLE_EQ(selection.score(f, 1).f1, evaluate_learned(b, replay_evidence(b, options), options.linkage).f1);
}

TEST(GroupSelection, StandardFamiliesAndTheDefault) {
  const auto families = standard_group_families();
  ASSERT_EQ(families.size(), 16u);
  EXPECT_EQ(families.front().name, "plain rule 2.0 m / 0.4 m/s, linkage none");
  EXPECT_EQ(families.back().name, "chosen among all of the above");
  const GroupFamily d = default_group_family();
  EXPECT_EQ(d.name, "learned rule, whole common time, linkage chosen");
  ASSERT_EQ(d.grid.size(), 12u);  // 3 linkages x 2 velocity spans x 2 min-moving shares
  EXPECT_EQ(d.grid.front().linkage, GroupLinkage::kSingle);
  EXPECT_TRUE(std::isinf(d.grid.front().window_s));
  EXPECT_EQ(d.grid.front().velocity_span_s, 0.4);
  EXPECT_EQ(rule_threshold_grid().size(), 29u * 20u);
}

}  // namespace
}  // namespace bodyrec
