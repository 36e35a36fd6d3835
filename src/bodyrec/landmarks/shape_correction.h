// A linear correction of fitted landmarks, learnt on the training people by ridge regression: the fitted
// points, in box units, map to where the true points lie. The mask network's outline is mostly in place,
// but its landmarks slide along it where the outline's length is spread unlike the truth's (a gap between
// the legs closed or opened, an arm against the body); how far they slide goes with the fitted shape
// itself, which a per-landmark mean (the arc offsets) cannot follow. On the Penn-Fudan validation people
// it takes 6.14 % of the box height to 5.96 % (docs/benchmarks.md, "Linear shape correction").
#pragma once

#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/core/geometry.h"

namespace bodyrec {

// Chosen on the Penn-Fudan validation people with two networks (docs/benchmarks.md).
inline constexpr double kShapeCorrectionRidge = 3.0;

class ShapeCorrection {
 public:
  ShapeCorrection() = default;  // empty: apply() returns its input

  // Ridge regression from the fitted points to the true ones, both in box units (x from the box's centre,
  // y from its top, each divided by the box's height): true = fitted + bias + (fitted - mean) W, W
  // minimising the squared error plus `ridge` |W|^2. REQUIRES: fitted, truth and boxes have the same
  // number of people (>= 1), every shape the same number of points (>= 1), boxes taller than 0, ridge > 0.
  // Throws ProcessingError when the solution is not finite (a point that is not a number).
  static ShapeCorrection learn(const std::vector<std::vector<cv::Point2d>>& fitted,
                               const std::vector<std::vector<cv::Point2d>>& truth, const std::vector<Box>& boxes,
                               double ridge);

  bool empty() const { return bias_.empty(); }
  int landmarks() const { return static_cast<int>(bias_.size() / 2); }

  // The corrected points of a person in `box`. REQUIRES: points.size() == landmarks() unless empty().
  std::vector<cv::Point2d> apply(const std::vector<cv::Point2d>& points, const Box& box) const;

  // dlib serialisation (the mean, the bias, the weights). read() throws InputError naming `name` when the
  // stream ends early or the sizes do not fit `landmarks` or a value is not finite.
  void write(std::ostream& out) const;
  static ShapeCorrection read(std::istream& in, int landmarks, const std::string& name);

 private:
  std::vector<double> mean_;   // 2N: the training people's mean fitted shape, x0 y0 x1 y1 ...
  std::vector<double> bias_;   // 2N: their mean (true - fitted)
  std::vector<float> weights_; // 2N x 2N, row-major: (fitted - mean) [row] -> correction [column]
};

}  // namespace bodyrec
