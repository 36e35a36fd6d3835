#include "bodyrec/reid/open_set.h"

#include <algorithm>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

namespace bodyrec {
namespace {

// Gallery: identities 10, 11, 12 (enrolled) and 99 (seen by the gallery camera only). Probes 0-2 are
// the enrolled people (probe 1 is closest to the distractor), probes 3-7 strangers whose best
// similarities are 0.4, 0.8, 0.35, 0.65, 0.2.
struct Toy {
  std::vector<int> probe_ids = {10, 11, 12, 13, 14, 15, 16, 17};
  std::vector<int> gallery_ids = {10, 11, 12, 99};
  cv::Mat similarity = (cv::Mat_<double>(8, 4) << 0.9, 0.1, 0.2, 0.3,  //
                        0.1, 0.5, 0.2, 0.6,                            //
                        0.2, 0.1, 0.7, 0.3,                            //
                        0.1, 0.2, 0.4, 0.1,                            //
                        0.8, 0.1, 0.1, 0.1,                            //
                        0.3, 0.35, 0.1, 0.2,                           //
                        0.1, 0.1, 0.1, 0.65,                           //
                        0.05, 0.1, 0.2, 0.1);
};

TEST(OpenSet, ProbesKnowTheirBestMatchAndWhetherTheyAreEnrolled) {
  const Toy t;
  const auto probes = open_set_probes(t.similarity, t.probe_ids, t.gallery_ids);
  ASSERT_EQ(probes.size(), 8u);
  EXPECT_TRUE(probes[0].enrolled && probes[0].own_first);
  EXPECT_TRUE(probes[1].enrolled && !probes[1].own_first);  // the distractor is closer
  EXPECT_DOUBLE_EQ(probes[1].best, 0.6);
  EXPECT_FALSE(probes[4].enrolled || probes[4].own_first);
  EXPECT_DOUBLE_EQ(probes[4].best, 0.8);
  // A tie between the own identity and another is not a first place.
  const cv::Mat tie = (cv::Mat_<double>(1, 2) << 0.5, 0.5);
  EXPECT_FALSE(open_set_probes(tie, {1}, {1, 2})[0].own_first);
}

TEST(OpenSet, DirAtFarPutsTheThresholdAtTheStrangersScores) {
  const Toy t;
  const auto probes = open_set_probes(t.similarity, t.probe_ids, t.gallery_ids);
  // 5 strangers: FAR 1 % and 10 % accept none (threshold 0.8): only probe 0 (0.9) is detected.
  EXPECT_DOUBLE_EQ(dir_at_far(probes, 0.01), 1.0 / 3);
  EXPECT_DOUBLE_EQ(dir_at_far(probes, 0.10), 1.0 / 3);
  // FAR 20 % accepts one stranger (threshold 0.65): probe 2 (0.7) is detected too.
  EXPECT_DOUBLE_EQ(dir_at_far(probes, 0.20), 2.0 / 3);
  // Accepting every stranger leaves the identification errors: probe 1 is never detected.
  EXPECT_DOUBLE_EQ(dir_at_far(probes, 1.0), 2.0 / 3);
  // No stranger: nothing is rejected; no enrolled probe: 0.
  const std::vector<OpenSetProbe> only_enrolled = {probes[0], probes[1]};
  EXPECT_DOUBLE_EQ(dir_at_far(only_enrolled, 0.01), 0.5);
  const std::vector<OpenSetProbe> only_strangers = {probes[3], probes[4]};
  EXPECT_DOUBLE_EQ(dir_at_far(only_strangers, 0.5), 0.0);
}

TEST(OpenSet, ScoresAtAFixedThreshold) {
  const Toy t;
  OpenSetScores s = open_set_scores(t.similarity, t.probe_ids, t.gallery_ids, 0.5);
  EXPECT_EQ(s.enrolled, 3);
  EXPECT_EQ(s.strangers, 5);
  EXPECT_DOUBLE_EQ(s.dir_far1, 1.0 / 3);
  EXPECT_DOUBLE_EQ(s.dir_far10, 1.0 / 3);
  EXPECT_DOUBLE_EQ(s.rank1_closed, 2.0 / 3);
  EXPECT_DOUBLE_EQ(s.dir_at_threshold, 2.0 / 3);  // probes 0 and 2; probe 1 is accepted as someone else
  EXPECT_DOUBLE_EQ(s.far_at_threshold, 2.0 / 5);  // strangers at 0.8 and 0.65
  EXPECT_DOUBLE_EQ(s.missed_at_threshold, 0.0);
  s = open_set_scores(t.similarity, t.probe_ids, t.gallery_ids, 0.75);
  EXPECT_DOUBLE_EQ(s.dir_at_threshold, 1.0 / 3);
  EXPECT_DOUBLE_EQ(s.far_at_threshold, 1.0 / 5);
  EXPECT_DOUBLE_EQ(s.missed_at_threshold, 2.0 / 3);  // probes 1 (0.6) and 2 (0.7) would be enrolled again
}

TEST(OpenSet, EnrolsARandomHalfOfTheTestIdentities) {
  const std::vector<int> ids = {3, 5, 8, 13, 21, 34, 55};
  const auto a = enrolled_identities(ids, 0, 0);
  ASSERT_EQ(a.size(), 3u);
  EXPECT_TRUE(std::is_sorted(a.begin(), a.end()));
  for (int id : a) EXPECT_NE(std::find(ids.begin(), ids.end(), id), ids.end()) << id;
  EXPECT_EQ(enrolled_identities(ids, 0, 0), a);  // deterministic
  bool differs = false;
  for (int split = 1; split < 5; ++split) differs |= enrolled_identities(ids, 0, split) != a;
  EXPECT_TRUE(differs);
  EXPECT_EQ(enrolled_identities({7}, 0, 0).size(), 0u);
}

}  // namespace
}  // namespace bodyrec
