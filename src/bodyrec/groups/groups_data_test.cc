// Group membership on the real walking-group scenes (EWAP seq_eth, seq_hotel; UCY zara01): pair counts,
// the plain rule, the default method in nested leave-one-scene-out (the built-in models are its fits),
// that the fast scoring of model selection gives what replaying through GroupMembership gives, and that
// the built-in models are what training reproduces.
#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

#include "bodyrec/groups/group_selection.h"
#include "test_support.h"

namespace bodyrec::testing {
namespace {

struct SceneCase {
  const char* path;
  int rows;
  int pairs;           // co-present pairs
  int labelled_pairs;  // of those, together in groups.txt
  double rule_f1;      // measured: plain rule, median distance <= 2 m, median speed difference <= 0.4 m/s
  double default_f1;   // measured: the default family, chosen and fitted on the two other scenes
};

const SceneCase kScenes[] = {
    {"walking_groups/ETH/seq_eth", 8908, 2524, 175, 0.6854, 0.7419},
    {"walking_groups/ETH/seq_hotel", 6544, 2025, 47, 0.4677, 0.7231},
    {"walking_groups/UCY/zara01", 5024, 849, 73, 0.7614, 0.9178},
};

std::vector<WalkingScene> all_scenes() {
  std::vector<WalkingScene> scenes;
  for (const auto& c : kScenes) {
    const auto dir = data_path(c.path);
    if (dir.empty()) return {};
    scenes.push_back(read_walking_scene(dir.string()));
  }
  return scenes;
}

#define REQUIRE_ALL_SCENES(scenes)                                                          \
  const std::vector<WalkingScene> scenes = all_scenes();                                    \
  if (scenes.empty())                                                                       \
  GTEST_SKIP() << "walking_groups scenes not found under BODYREC_DATA (" << data_root_description() << ")"

TEST(WalkingGroupsData, ScenesParseWithTheirFramePeriodAndPairCounts) {
  for (const auto& c : kScenes) {
    BODYREC_REQUIRE_DATA(dir, c.path);
    const WalkingScene scene = read_walking_scene(dir.string());
    EXPECT_EQ(static_cast<int>(scene.rows.size()), c.rows) << c.path;
    // Every scene is annotated every 0.4 s: 6 frames of 15 fps (eth) or 10 frames of 25 fps (hotel, zara).
    const double step = scene.name == "seq_eth" ? 6 : 10;
    EXPECT_NEAR(scene.seconds_per_frame * step, 0.4, 0.01) << c.path;
    const PairScores s = score_pairs(scene, [](int, int) { return true; });
    EXPECT_EQ(s.pairs, c.pairs) << c.path;
    EXPECT_EQ(s.labelled_pairs, c.labelled_pairs) << c.path;
  }
}

TEST(WalkingGroupsData, PlainRuleScores) {
  for (const auto& c : kScenes) {
    BODYREC_REQUIRE_DATA(dir, c.path);
    const WalkingScene scene = read_walking_scene(dir.string());
    EXPECT_NEAR(evaluate_threshold(scene, 2.0, 0.4, 0.4).f1, c.rule_f1, 1e-4) << c.path;
  }
}

TEST(WalkingGroupsData, DefaultMethodInNestedLeaveOneSceneOutBeatsThePlainRule) {
  REQUIRE_ALL_SCENES(scenes);
  GroupSelection selection(scenes);
  const NestedResult result = selection.nested_loso(default_group_family());
  ASSERT_EQ(result.folds.size(), 3u);
  for (size_t s = 0; s < 3; ++s) {
    const NestedFold& f = result.folds[s];
    EXPECT_EQ(f.scene, scenes[s].name);
    EXPECT_NEAR(f.scores.f1, kScenes[s].default_f1, 1e-4) << f.scene;
    EXPECT_GT(f.scores.f1, kScenes[s].rule_f1) << f.scene;  // on every scene
    // Chosen within the two other scenes: single linkage each time; the velocity span differs.
    EXPECT_EQ(f.chosen.linkage, GroupLinkage::kSingle) << f.scene;
    EXPECT_EQ(f.chosen.velocity_span_s, s == 1 ? 2.0 : 0.4) << f.scene;
  }
  EXPECT_NEAR(result.mean_f1, 0.7943, 1e-4);
}

TEST(WalkingGroupsData, BuiltinModelReplayedThroughGroupMembershipGivesTheNestedScores) {
  for (const auto& c : kScenes) {
    BODYREC_REQUIRE_DATA(dir, c.path);
    const WalkingScene scene = read_walking_scene(dir.string());
    const GroupOptions options = options_for(std::make_shared<const PairModel>(builtin_pair_model_for(scene.name)));
    ASSERT_FALSE(options.model->trained_on_scene(scene.name));
    const PairScores s = evaluate_learned(scene, replay_evidence(scene, options), options.linkage);
    EXPECT_NEAR(s.f1, c.default_f1, 1e-4) << c.path;
  }
}

TEST(WalkingGroupsData, WindowEvidenceIsTheReplayedEvidence) {
  BODYREC_REQUIRE_DATA(dir, "walking_groups/ETH/seq_hotel");
  const WalkingScene scene = read_walking_scene(dir.string());
  const ScenePairs pairs = scene_pairs(scene, 0.4);
  for (const PairModel& model : {builtin_pair_model_for("seq_hotel"), builtin_pair_model_for("")}) {
    GroupOptions options = options_for(std::make_shared<const PairModel>(model));
    for (double window : {std::numeric_limits<double>::infinity(), 8.0}) {
      options.window_s = window;
      PairModel m = model;
      m.window_s = window;
      const auto windows = scene_windows(scene, pairs, options);
      const auto fast = window_evidence(pairs, windows, m, options.min_moving_fraction);
      const auto replayed = replay_evidence(scene, options);
      size_t known = 0;
      for (size_t p = 0; p < pairs.pairs.size(); ++p) {
        const auto it = replayed.find(pairs.pairs[p]);
        if (it == replayed.end()) {
          EXPECT_TRUE(std::isnan(fast[p]));
        } else {
          EXPECT_EQ(fast[p], it->second);
          ++known;
        }
      }
      EXPECT_EQ(known, replayed.size());
      EXPECT_GT(known, 500u);
    }
  }
}

TEST(WalkingGroupsData, BuiltinModelsAreReproducedByTraining) {
  REQUIRE_ALL_SCENES(scenes);
  for (const PairModel& builtin : builtin_pair_models()) {
    std::vector<WalkingScene> training;
    for (const auto& scene : scenes)
      if (builtin.trained_on_scene(scene.name)) training.push_back(scene);
    ASSERT_EQ(training.size(), builtin.trained_on.size());
    GroupSelection selection(training);
    std::vector<size_t> all(training.size());
    for (size_t s = 0; s < all.size(); ++s) all[s] = s;
    EXPECT_EQ(to_text(*selection.select_and_fit(default_group_family(), all).model), to_text(builtin));
  }
}

}  // namespace
}  // namespace bodyrec::testing
