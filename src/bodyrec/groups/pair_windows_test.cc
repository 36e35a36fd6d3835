// The per-scene cache of model selection on hand-made scenes: pairs, labels, rule statistics, and that
// evidence from cached windows is exactly what replaying the scene through GroupMembership gives (also
// when a person is forgotten and comes back, and over the whole common time).
#include "bodyrec/groups/pair_windows.h"

#include <cmath>
#include <functional>
#include <limits>

#include <gtest/gtest.h>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// Frames every 0.4 s; `at(id, t)` gives a position or nothing (not in view).
WalkingScene make_scene(int frames, const std::vector<int>& ids,
                        const std::function<std::optional<cv::Point2d>(int, double)>& at,
                        std::vector<std::vector<int>> groups) {
  WalkingScene scene;
  scene.name = "hand_made";
  scene.seconds_per_frame = 0.4;
  for (int f = 0; f < frames; ++f)
    for (int id : ids)
      if (const auto p = at(id, 0.4 * f)) {
        ObsmatRow r;
        r.frame = f;
        r.person = id;
        r.position = *p;
        scene.rows.push_back(r);
      }
  scene.groups = std::move(groups);
  return scene;
}

// 1 and 2 walk east 0.6 m apart; 3 walks with them 2.5 m away (not labelled); 4 and 5 stand 1 m apart;
// 6 crosses. 2 leaves the view from 10 s to 14 s (longer than forget_after_s) and comes back 3 m away.
WalkingScene scene_with_a_gap() {
  return make_scene(50, {1, 2, 3, 4, 5, 6}, [](int id, double t) -> std::optional<cv::Point2d> {
    switch (id) {
      case 1: return cv::Point2d(1.2 * t, 0);
      case 2:
        if (t > 10 && t < 14) return std::nullopt;
        return cv::Point2d(1.2 * t, t < 10 ? 0.6 : 3.0);
      case 3: return cv::Point2d(1.2 * t, -2.5);
      case 4: return cv::Point2d(5, 8);
      case 5: return cv::Point2d(6, 8);
      default: return cv::Point2d(12, -10 + 1.4 * t);
    }
  }, {{1, 2}, {4}});
}

PairModel rule_model(double window_s) {
  PairModel m;
  m.rule = true;
  m.max_distance_m = 1.3;
  m.max_speed_difference = 0.2;
  m.weights[0] = 4;
  m.scale.fill(1);
  m.window_s = window_s;
  m.velocity_span_s = 0.4;
  return m;
}

TEST(ScenePairs, PairsLabelsAndRuleStatistics) {
  const WalkingScene scene = scene_with_a_gap();
  const ScenePairs p = scene_pairs(scene, 0.4);
  EXPECT_EQ(p.ids, (std::vector<int>{1, 2, 3, 4, 5, 6}));
  ASSERT_EQ(p.pairs.size(), 15u);  // everyone is seen with everyone
  EXPECT_EQ(p.index(2, 1), 0);
  EXPECT_EQ(p.index(1, 2), 0);
  EXPECT_EQ(p.index(1, 7), -1);
  const int walkers = p.index(1, 2), standing = p.index(4, 5), beside = p.index(1, 3);
  EXPECT_TRUE(p.labelled[walkers]);
  EXPECT_FALSE(p.labelled[standing]);
  EXPECT_NEAR(p.median_distance[standing], 1.0, 1e-12);
  EXPECT_NEAR(p.median_speed_difference[standing], 0.0, 1e-12);
  EXPECT_NEAR(p.median_distance[beside], 2.5, 1e-9);
  // The plain rule (2 m, 0.4 m/s) takes the standing pair, not the walker 2.5 m beside.
  const auto rule = rule_evidence(p, 2.0, 0.4);
  EXPECT_EQ(rule[standing], 1.0);
  EXPECT_EQ(rule[beside], -1.0);
  EXPECT_THROW(scene_pairs(scene, 0), UsageError);
}

TEST(ScenePairs, WindowEvidenceIsWhatReplayingThroughGroupMembershipGives) {
  const WalkingScene scene = scene_with_a_gap();
  const ScenePairs p = scene_pairs(scene, 0.4);
  for (double window : {4.0, 8.0, std::numeric_limits<double>::infinity()})
    for (double moving : {0.0, 0.5}) {
      GroupOptions options;
      options.window_s = window;
      options.min_moving_fraction = moving;
      options.model = std::make_shared<const PairModel>(rule_model(window));
      const auto windows = scene_windows(scene, p, options);
      const auto fast = window_evidence(p, windows, *options.model, moving);
      const auto replayed = replay_evidence(scene, options);
      for (size_t q = 0; q < p.pairs.size(); ++q) {
        const auto it = replayed.find(p.pairs[q]);
        if (it == replayed.end()) {
          EXPECT_TRUE(std::isnan(fast[q])) << q;
        } else {
          EXPECT_EQ(fast[q], it->second) << q << " window " << window;
        }
      }
      // 2 was forgotten and came back 3 m away: the pair's evidence starts again, so it is apart.
      const int walkers = p.index(1, 2);
      int epochs = 0;
      for (const auto& w : windows)
        if (w.pair == walkers) epochs = std::max(epochs, w.epoch);
      EXPECT_EQ(epochs, 1);
      EXPECT_LT(fast[walkers], 0) << window;
      // Standing still: no window counts with min-moving 0.5.
      EXPECT_EQ(std::isnan(fast[p.index(4, 5)]), moving > 0) << window;
    }
}

TEST(ScenePairs, ExamplesWeighEveryPairOnce) {
  const WalkingScene scene = scene_with_a_gap();
  const ScenePairs p = scene_pairs(scene, 0.4);
  GroupOptions options;
  options.window_s = 8;
  const auto windows = scene_windows(scene, p, options);
  const auto examples = window_examples(p, windows, 0.5);
  double total = 0;
  int together = 0;
  for (const auto& e : examples) {
    total += e.weight;
    together += e.together;
  }
  EXPECT_NEAR(total, 6.0, 1e-9);  // the pairs of the walkers 1, 2, 3, 6: 4 and 5 never walk
  EXPECT_GT(together, 0);
}

TEST(ScenePairs, ScoringWithAndWithoutGroupConsistency) {
  WalkingScene scene = make_scene(3, {1, 2, 3, 4}, [](int id, double) { return cv::Point2d(id, 0); },
                                  {{1, 2, 3}});
  const ScenePairs p = scene_pairs(scene, 0.4);
  ASSERT_EQ(p.pairs.size(), 6u);
  const double unknown = std::numeric_limits<double>::quiet_NaN();
  // (1,2) (1,3) (1,4) (2,3) (2,4) (3,4)
  const std::vector<double> e = {2.0, -0.5, -3.0, 1.0, -3.0, unknown};
  PairScores s = score_evidence(p, e, GroupLinkage::kNone);
  EXPECT_EQ(s.predicted_pairs, 2);
  EXPECT_EQ(s.true_pairs, 2);
  EXPECT_NEAR(s.recall, 2.0 / 3, 1e-12);
  s = score_evidence(p, e, GroupLinkage::kSingle);  // 1-2 and 2-3 put 1 and 3 together
  EXPECT_EQ(s.predicted_pairs, 3);
  EXPECT_DOUBLE_EQ(s.f1, 1.0);
  s = score_evidence(p, e, GroupLinkage::kAverage);
  EXPECT_EQ(s.predicted_pairs, 3);
  s = score_evidence(p, e, GroupLinkage::kSingle, -1.5);  // only 1-2 stays above 0
  EXPECT_EQ(s.predicted_pairs, 1);
  EXPECT_THROW(score_evidence(p, {1.0}, GroupLinkage::kNone), UsageError);
}

}  // namespace
}  // namespace bodyrec
