#include "bodyrec/reid/cmc.h"

#include <algorithm>
#include <numeric>

namespace bodyrec {

RankingScores ranking_scores(const cv::Mat& similarity, const std::vector<int>& probe_ids,
                             const std::vector<int>& gallery_ids, int max_rank) {
  CV_Assert(similarity.type() == CV_64F && similarity.rows == static_cast<int>(probe_ids.size()) &&
            similarity.cols == static_cast<int>(gallery_ids.size()) && max_rank >= 1);
  RankingScores out;
  out.cmc.assign(static_cast<size_t>(max_rank), 0.0);
  const int n = similarity.cols;
  std::vector<int> order(static_cast<size_t>(n));
  for (int p = 0; p < similarity.rows; ++p) {
    const double* s = similarity.ptr<double>(p);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return s[a] > s[b]; });
    // Walk tie groups in descending similarity.
    int before = 0, correct_before = 0;
    double ap = 0;
    bool found = false;
    for (int i = 0; i < n;) {
      int j = i, correct = 0;
      while (j < n && s[order[j]] == s[order[i]]) correct += gallery_ids[order[j]] == probe_ids[p], ++j;
      const int size = j - i, wrong = size - correct;
      if (correct > 0) {
        if (!found)  // first correct image: CMC as a probability over the tie order
          for (int k = before + 1; k <= max_rank; ++k) {
            double all_wrong = 1;  // the first k - before of the group are all wrong
            for (int t = 0; t < k - before; ++t) all_wrong *= t < wrong ? double(wrong - t) / (size - t) : 0.0;
            out.cmc[k - 1] += 1.0 - all_wrong;
          }
        found = true;
        for (int c = 1; c <= correct; ++c) {  // expected position of the c-th correct one in the group
          const double position = before + c * double(size + 1) / (correct + 1);
          ap += (correct_before + c) / position;
        }
        correct_before += correct;
      }
      before += size;
      i = j;
    }
    if (!found) continue;
    out.map += ap / correct_before;
    ++out.probes;
  }
  if (out.probes > 0) {
    for (double& c : out.cmc) c /= out.probes;
    out.map /= out.probes;
  }
  return out;
}

}  // namespace bodyrec
