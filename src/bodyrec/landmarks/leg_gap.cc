#include "bodyrec/landmarks/leg_gap.h"

#include <algorithm>
#include <limits>
#include <vector>

#include <opencv2/core.hpp>

namespace bodyrec {

int cut_leg_gap(cv::Mat& mask, const cv::Mat& logits, double slit_logit) {
  CV_Assert(mask.type() == CV_8UC1 && logits.type() == CV_32FC1 && mask.size() == logits.size());
  const int h = mask.rows, w = mask.cols, top = h / 2;
  if (h < 2 || w < 3) return 0;
  constexpr double kUnreachable = std::numeric_limits<double>::infinity();
  // Least summed logit of a path from row `top` to each pixel (dynamic programming, row by row; rows
  // below `top` only, stored from row 0 = `top`), using only the columns strictly between the row's
  // outermost body pixels.
  const int rows = h - top;
  std::vector<double> cost(static_cast<size_t>(rows) * w, kUnreachable);
  std::vector<int> from(static_cast<size_t>(rows) * w, -1);
  for (int i = 0; i < rows; ++i) {
    const uchar* m = mask.ptr<uchar>(top + i);
    const int left = static_cast<int>(std::find_if(m, m + w, [](uchar v) { return v != 0; }) - m);
    int right = w - 1;
    while (right > left && !m[right]) --right;
    const float* l = logits.ptr<float>(top + i);
    double* here = &cost[static_cast<size_t>(i) * w];
    int* back = &from[static_cast<size_t>(i) * w];
    for (int c = left + 1; c < right; ++c) {
      if (i == 0) {
        here[c] = l[c];
        continue;
      }
      const double* above = here - w;
      int best = c;
      if (c > 0 && above[c - 1] < above[best]) best = c - 1;
      if (c + 1 < w && above[c + 1] < above[best]) best = c + 1;
      if (above[best] < kUnreachable) {
        here[c] = above[best] + l[c];
        back[c] = best;
      }
    }
  }
  // The valley ends in the lowest row it reaches, at that row's cheapest pixel.
  int last = rows - 1, end = 0;
  for (; last >= 0; --last) {
    const double* row = &cost[static_cast<size_t>(last) * w];
    end = static_cast<int>(std::min_element(row, row + w) - row);
    if (row[end] < kUnreachable) break;
  }
  if (last < 0) return 0;
  const int bottom = top + last;
  std::vector<int> valley(h, -1);
  for (int r = bottom, c = end; r >= top; c = from[static_cast<size_t>(r - top) * w + c], --r) valley[r] = c;
  int first = bottom + 1;  // the slit's top row
  while (first > top && logits.at<float>(first - 1, valley[first - 1]) < slit_logit) --first;
  if (first > bottom) return 0;
  for (int r = first; r <= bottom; ++r) {
    // Also the pixel where the valley steps sideways, so that the slit stays 4-connected.
    const int next = r < bottom ? valley[r + 1] : valley[r];
    for (int c = std::min(valley[r], next); c <= std::max(valley[r], next); ++c) mask.at<uchar>(r, c) = 0;
  }
  for (int r = bottom + 1; r < h; ++r) mask.at<uchar>(r, valley[bottom]) = 0;
  return h - first;
}

}  // namespace bodyrec
