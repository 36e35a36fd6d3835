#include "shape_body_mask.h"

#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace bodyrec::cli {

cv::Mat ShapeBodyMask::mask(const cv::Mat& frame, const cv::Rect& box) {
  const cv::Rect b = box & cv::Rect(0, 0, frame.cols, frame.rows);
  if (b.empty()) return {};
  if (prepared_for_ != frame.data || prepared_.size() != frame.size()) {
    prepared_ = model_.prepare(frame);
    prepared_for_ = frame.data;
  }
  const std::vector<cv::Point2d> outline = model_.fit(prepared_, Box(b));
  std::vector<cv::Point> polygon;
  for (const cv::Point2d& p : outline)
    polygon.emplace_back(static_cast<int>(std::lround(p.x)) - b.x, static_cast<int>(std::lround(p.y)) - b.y);
  cv::Mat out = cv::Mat::zeros(b.size(), CV_8U);
  if (polygon.size() >= 3) cv::fillPoly(out, std::vector<std::vector<cv::Point>>{polygon}, cv::Scalar(255));
  return out;
}

std::string ShapeBodyMask::describe() const { return "body shape model (" + model_.kind_name() + ")"; }

}  // namespace bodyrec::cli
