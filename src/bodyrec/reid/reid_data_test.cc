// The matchers on VIPeR (632 people, two cameras, 48x128): the default (its variant chosen inside each
// split's training people) and the published LOMO + XQDA must keep their measured rank-1, and the
// thesis's KAZE score is measured (near chance across cameras, as the digest reports). Fewer splits than
// the 10 of the protocol keep the test short; docs/benchmarks.md has the full figures.
#include <gtest/gtest.h>

#include "bodyrec/reid/reid_eval.h"
#include "test_support.h"

namespace bodyrec {
namespace {

// Measured rank-1 on split 0 of seed 0 minus a small margin (docs/benchmarks.md has the 10-split figures):
// default 45.25 % (the mirror-averaged LOMO alone, the default before GOG, scored 37.34 %, which this
// floor rejects), the published LOMO + XQDA 29.43 % (solved as XQDA.m; 30.70 % with the generalised
// eigen solver), the unlearned fallback 14.56 %.
constexpr double kDefaultRank1Floor = 0.43;
constexpr double kPublishedRank1Floor = 0.28;
constexpr double kLomoRank1Floor = 0.13;

ReidDataset viper(const std::filesystem::path& root) {
  return scan_reid_dataset(root.string(), "^images/(\\d{4})", "^images/\\d{4}(\\d{4})");
}

TEST(ViperData, DefaultMatcherReachesItsRank1) {
  BODYREC_REQUIRE_DATA(root, "viper");
  const ReidDataset data = viper(root);
  ASSERT_EQ(data.images.size(), 1264u);
  ASSERT_EQ(data.in_both.size(), 632u);
  ReidEvalOptions o;
  o.train_ids = 316;
  o.splits = 1;
  const ReidEvalResult r = evaluate_reid(data, [] { return make_untrained_matcher("default"); }, o);
  EXPECT_EQ(r.probes, 316);
  EXPECT_EQ(r.gallery, 316);
  EXPECT_GE(r.rank1, kDefaultRank1Floor) << r.matcher;
  EXPECT_GE(r.rank20, 0.9);  // 95.89 %
  // The learned same-person threshold holds for the test's new people (split 0: 97.2 % of same-person
  // pairs accepted, 92.2 % of different-person pairs rejected; the calibration on training pairs it
  // replaced accepted 8.2 %).
  EXPECT_GE(r.same_accepted, 0.85);
  EXPECT_GE(r.different_rejected, 0.85);
  const ReidEvalResult published = evaluate_reid(data, [] { return make_untrained_matcher("lomo-xqda"); }, o);
  EXPECT_GE(published.rank1, kPublishedRank1Floor) << published.matcher;
  EXPECT_GT(r.rank1, published.rank1 + 0.1);
}

// Open set on split 0 (docs/benchmarks.md): 158 enrolled, 158 strangers; the published recipe names
// 41.1 % of the enrolled at rank 1, 8.9 % at FAR 10 %, and at its calibrated threshold accepts 98.1 % of
// the strangers.
TEST(ViperData, OpenSetSplitsTheTestPeopleInHalves) {
  BODYREC_REQUIRE_DATA(root, "viper");
  const ReidDataset data = viper(root);
  ReidEvalOptions o;
  o.train_ids = 316;
  o.splits = 1;
  o.open_set = true;
  const ReidEvalResult r = evaluate_reid(data, [] { return make_untrained_matcher("lomo-xqda"); }, o);
  ASSERT_EQ(r.open_set_per_split.size(), 1u);
  EXPECT_EQ(r.open_set.enrolled, 158);
  EXPECT_EQ(r.open_set.strangers, 158);
  EXPECT_NEAR(r.open_set.rank1_closed, 0.411, 0.02) << r.matcher;
  EXPECT_NEAR(r.open_set.dir_far10, 0.089, 0.02);
  EXPECT_LE(r.open_set.dir_far1, r.open_set.dir_far10);
  EXPECT_GT(r.open_set.far_at_threshold, 0.9);
  EXPECT_DOUBLE_EQ(r.rank1, r.rank1_per_split[0]);  // the closed-set figures are still there
}

TEST(ViperData, UnlearnedFallbackAndKazeAreMeasured) {
  BODYREC_REQUIRE_DATA(root, "viper");
  const ReidDataset data = viper(root);
  ReidEvalOptions o;
  o.train_ids = 316;
  o.splits = 1;
  const ReidEvalResult lomo = evaluate_reid(data, [] { return make_untrained_matcher("lomo"); }, o);
  EXPECT_GE(lomo.rank1, kLomoRank1Floor);
  EXPECT_GE(lomo.same_accepted, 0.5);
  EXPECT_GE(lomo.different_rejected, 0.5);
  const ReidEvalResult kaze = evaluate_reid(data, [] { return make_untrained_matcher("kaze"); }, o);
  EXPECT_EQ(kaze.probes, 316);
  EXPECT_LT(kaze.rank1, 0.03);  // near chance (1/316 = 0.3 %): KAZE does not carry across cameras
  EXPECT_GT(kaze.rank20, 0.0);
}

}  // namespace
}  // namespace bodyrec
