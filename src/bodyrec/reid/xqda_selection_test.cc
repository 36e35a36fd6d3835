#include "bodyrec/reid/xqda_selection.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// Two blocks of 40 values per image: block 0 carries the identity (plus camera noise), block 1 is noise.
struct Blocks {
  std::vector<cv::Mat> grams;
  std::vector<XqdaLabel> labels;
};

Blocks make_blocks(int identities, uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat signal(2 * identities, 40, CV_32F), noise(2 * identities, 40, CV_32F);
  Blocks b;
  for (int id = 0; id < identities; ++id) {
    cv::Mat person(1, 40, CV_32F);
    rng.fill(person, cv::RNG::NORMAL, 0, 1);
    for (int cam = 0; cam < 2; ++cam) {
      const int row = 2 * id + cam;
      cv::Mat jitter(1, 40, CV_32F);
      rng.fill(jitter, cv::RNG::NORMAL, 0, 0.5);
      signal.row(row) = person + jitter;
      rng.fill(noise.row(row), cv::RNG::NORMAL, 0, 1);
      b.labels.push_back({id, cam});
    }
  }
  b.grams = {gram_matrix(signal), gram_matrix(noise)};
  return b;
}

TEST(XqdaSelection, ChoosesTheVariantThatRecognisesHeldOutPeople) {
  const Blocks b = make_blocks(60, 1);
  // Fusing a noise model adds its distances; one XQDA over both blocks learns to ignore the noise.
  const std::vector<XqdaVariant> variants = {{"noise", {{1}}}, {"signal", {{0}}}, {"both-fused", {{0}, {1}}}};
  const XqdaSelection s = select_xqda_variant(b.grams, b.labels, variants, 4);
  ASSERT_EQ(s.score.size(), 3u);
  EXPECT_EQ(s.chosen, 1);
  EXPECT_GT(s.score[1], 0.85);  // held-out mAP of the signal block (0.898)
  EXPECT_LT(s.score[0], 0.3);  // noise: about chance (mean reciprocal rank over 15 people per fold)
  EXPECT_GT(s.score[1], s.score[2]);
  // The same data give the same folds and scores.
  EXPECT_EQ(select_xqda_variant(b.grams, b.labels, variants, 4).score, s.score);
}

TEST(XqdaSelection, RefusesTooFewPeopleAndBadBlocks) {
  const Blocks b = make_blocks(7, 2);
  const std::vector<XqdaVariant> variants = {{"signal", {{0}}}};
  EXPECT_THROW(select_xqda_variant(b.grams, b.labels, variants, 4), UsageError);  // 7 < 2 x 4
  EXPECT_NO_THROW(select_xqda_variant(b.grams, b.labels, variants, 3));
  EXPECT_THROW(select_xqda_variant(b.grams, b.labels, {{"bad", {{2}}}}, 3), UsageError);
  EXPECT_THROW(select_xqda_variant(b.grams, b.labels, {}, 3), UsageError);
  EXPECT_THROW(select_xqda_variant(b.grams, b.labels, variants, 1), UsageError);
}

}  // namespace
}  // namespace bodyrec
