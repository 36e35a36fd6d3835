#include "bodyrec/tracking/assignment.h"

#include <algorithm>
#include <cmath>

#include <dlib/matrix.h>
#include <dlib/optimization/max_cost_assignment.h>

namespace bodyrec {

std::vector<std::pair<int, int>> max_score_assignment(const std::vector<std::vector<double>>& score,
                                                      double min_score) {
  const int rows = static_cast<int>(score.size());
  const int cols = rows ? static_cast<int>(score[0].size()) : 0;
  std::vector<std::pair<int, int>> pairs;
  if (rows == 0 || cols == 0) return pairs;
  // dlib wants a square integer matrix: pad with zeros, and zero the gated-out entries so that the
  // optimum never trades a valid pair for an invalid one.
  const int n = std::max(rows, cols);
  dlib::matrix<long long> cost(n, n);
  cost = 0;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      if (score[r][c] >= min_score && score[r][c] > 0) cost(r, c) = std::llround(score[r][c] * 1e6);
  const std::vector<long> assignment = dlib::max_cost_assignment(cost);
  for (int r = 0; r < rows; ++r) {
    const int c = static_cast<int>(assignment[r]);
    if (c < cols && cost(r, c) > 0) pairs.emplace_back(r, c);
  }
  return pairs;
}

}  // namespace bodyrec
