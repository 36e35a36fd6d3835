// Ranking scores of re-identification: the CMC curve (share of probes whose first correct gallery image
// is within rank k) and mean average precision, from a probe x gallery similarity matrix.
#pragma once

#include <vector>

#include <opencv2/core/mat.hpp>

namespace bodyrec {

struct RankingScores {
  std::vector<double> cmc;  // cmc[k - 1] for k = 1..max_rank
  double map = 0;           // mean over probes of average precision
  int probes = 0;           // probes with at least one correct gallery image (the ones scored)
};

// REQUIRES similarity CV_64F, probe_ids.size() rows, gallery_ids.size() columns; higher = more alike.
// Ties are scored as their expectation under a random order: one correct image tied with e wrong ones
// after g strictly better wrong ones is within rank k with probability clamp((k - g) / (e + 1), 0, 1)
// (the general case: 1 - P(the first k - g of the group are all wrong)); for AP, the correct images of
// a tie group take their expected positions inside it. Probes with no
// correct gallery image are skipped (not counted in `probes`).
RankingScores ranking_scores(const cv::Mat& similarity, const std::vector<int>& probe_ids,
                             const std::vector<int>& gallery_ids, int max_rank = 20);

}  // namespace bodyrec
