// Optimal one-to-one assignment (Hungarian algorithm, dlib::max_cost_assignment) on a real-valued
// score matrix, shared by the tracker and the tracking metrics.
#pragma once

#include <utility>
#include <vector>

namespace bodyrec {

// `score[r][c]` for r in rows, c in columns (every row the same length; any shape, empty allowed).
// ENSURES: returns (row, column) pairs, sorted by row, of an assignment maximising the total score
//   over pairs whose score >= min_score; pairs below min_score (or <= 0) are never returned, and they
//   contribute nothing to the optimised total. Scores are scaled to integers with 1e-6 resolution.
// REQUIRES: min_score > 0; scores finite and below 1e12.
std::vector<std::pair<int, int>> max_score_assignment(const std::vector<std::vector<double>>& score,
                                                      double min_score);

}  // namespace bodyrec
