#include "bodyrec/landmarks/shape_correction.h"

#include <algorithm>
#include <cmath>

#include <dlib/serialize.h>
#include <opencv2/core.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

template <typename T>
bool all_finite(const std::vector<T>& values) {
  return std::all_of(values.begin(), values.end(), [](T v) { return std::isfinite(v); });
}

// A point in box units (x from the box's centre, y from its top, both / height): the same person at any
// size or place gives the same shape.
cv::Point2d box_units(const cv::Point2d& p, const Box& box) {
  return {(p.x - (box.x + box.width / 2)) / box.height, (p.y - box.y) / box.height};
}

// x0 y0 x1 y1 ... in box units.
void to_box_units(const std::vector<cv::Point2d>& points, const Box& box, double* out) {
  for (size_t k = 0; k < points.size(); ++k) {
    const cv::Point2d u = box_units(points[k], box);
    out[2 * k] = u.x;
    out[2 * k + 1] = u.y;
  }
}

}  // namespace

ShapeCorrection ShapeCorrection::learn(const std::vector<std::vector<cv::Point2d>>& fitted,
                                       const std::vector<std::vector<cv::Point2d>>& truth,
                                       const std::vector<Box>& boxes, double ridge) {
  CV_Assert(!fitted.empty() && fitted.size() == truth.size() && fitted.size() == boxes.size() && ridge > 0);
  const int people = static_cast<int>(fitted.size()), dims = static_cast<int>(2 * fitted[0].size());
  CV_Assert(dims > 0);
  cv::Mat x(people, dims, CV_64F), residual(people, dims, CV_64F);
  for (int i = 0; i < people; ++i) {
    CV_Assert(static_cast<int>(2 * fitted[i].size()) == dims && static_cast<int>(2 * truth[i].size()) == dims &&
              boxes[i].height > 0);
    to_box_units(fitted[i], boxes[i], x.ptr<double>(i));
    to_box_units(truth[i], boxes[i], residual.ptr<double>(i));
  }
  residual -= x;
  cv::Mat mean, bias;
  cv::reduce(x, mean, 0, cv::REDUCE_AVG);
  cv::reduce(residual, bias, 0, cv::REDUCE_AVG);
  const cv::Mat centred = x - cv::repeat(mean, people, 1);
  const cv::Mat target = residual - cv::repeat(bias, people, 1);
  cv::Mat normal = centred.t() * centred + ridge * cv::Mat::eye(dims, dims, CV_64F), weights;
  const bool solved = cv::solve(normal, centred.t() * target, weights, cv::DECOMP_CHOLESKY);
  ShapeCorrection c;
  c.mean_.assign(mean.begin<double>(), mean.end<double>());
  c.bias_.assign(bias.begin<double>(), bias.end<double>());
  c.weights_.assign(weights.begin<double>(), weights.end<double>());
  // Finite input and ridge > 0 make the system positive definite; anything else would be saved in a
  // model that read() then refuses, after the whole training.
  if (!solved || !all_finite(c.mean_) || !all_finite(c.bias_) || !all_finite(c.weights_))
    throw ProcessingError("shape correction: the ridge regression has no finite solution (a landmark that is not a number?)");
  return c;
}

std::vector<cv::Point2d> ShapeCorrection::apply(const std::vector<cv::Point2d>& points, const Box& box) const {
  if (empty()) return points;
  const int dims = static_cast<int>(bias_.size());
  CV_Assert(static_cast<int>(2 * points.size()) == dims);
  std::vector<float> centred(bias_.size());  // per person, so straight to the float the weights take
  for (size_t k = 0; k < points.size(); ++k) {
    const cv::Point2d u = box_units(points[k], box);
    centred[2 * k] = static_cast<float>(u.x - mean_[2 * k]);
    centred[2 * k + 1] = static_cast<float>(u.y - mean_[2 * k + 1]);
  }
  cv::Mat delta;  // gemm only reads the weights: the const_cast just wraps them without a copy
  cv::gemm(cv::Mat(1, dims, CV_32F, centred.data()), cv::Mat(dims, dims, CV_32F, const_cast<float*>(weights_.data())),
           1.0, cv::noArray(), 0.0, delta);
  const float* d = delta.ptr<float>(0);
  std::vector<cv::Point2d> out(points.size());
  for (size_t k = 0; k < points.size(); ++k)
    out[k] = points[k] + box.height * cv::Point2d(bias_[2 * k] + d[2 * k], bias_[2 * k + 1] + d[2 * k + 1]);
  return out;
}

void ShapeCorrection::write(std::ostream& out) const {
  dlib::serialize(mean_, out);
  dlib::serialize(bias_, out);
  dlib::serialize(weights_, out);
}

ShapeCorrection ShapeCorrection::read(std::istream& in, int landmarks, const std::string& name) {
  ShapeCorrection c;
  try {
    dlib::deserialize(c.mean_, in);
    dlib::deserialize(c.bias_, in);
    dlib::deserialize(c.weights_, in);
  } catch (const dlib::serialization_error&) {
    throw InputError(name + ": truncated mask-net model (shape correction)");
  }
  const size_t dims = 2 * static_cast<size_t>(landmarks);
  if (c.mean_.size() != dims || c.bias_.size() != dims || c.weights_.size() != dims * dims ||
      !all_finite(c.mean_) || !all_finite(c.bias_) || !all_finite(c.weights_))
    throw InputError(name + ": mask-net model has an invalid shape correction");
  return c;
}

}  // namespace bodyrec
