#include "bodyrec/store/scan_quality.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace bodyrec {

namespace {
constexpr double kSharpnessHalf = 100;   // Laplacian variance at which sharpness is 0.5
constexpr double kFullBodyPixels = 2000;  // fewer body pixels than this lowers completeness
}  // namespace

ScanQuality scan_quality(const cv::Mat& image, const cv::Mat& mask) {
  CV_Assert(!image.empty() && image.depth() == CV_8U);
  CV_Assert(mask.empty() || (mask.type() == CV_8UC1 && mask.size() == image.size()));
  ScanQuality q;
  cv::Mat body = mask.empty() ? cv::Mat(image.size(), CV_8UC1, cv::Scalar(255)) : (mask != 0);
  const int pixels = cv::countNonZero(body);
  if (pixels == 0) return q;

  cv::Mat grey, laplacian;
  if (image.channels() == 3)
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  else
    grey = image;
  cv::Laplacian(grey, laplacian, CV_64F);
  // Inside the body only: the mask's own edge against a black background is not sharpness.
  cv::Mat inner;
  cv::erode(body, inner, cv::Mat(), cv::Point(-1, -1), 2);
  if (cv::countNonZero(inner) == 0) inner = body;
  cv::Scalar mean, stddev;
  cv::meanStdDev(laplacian, mean, stddev, inner);
  const double variance = stddev[0] * stddev[0];
  q.sharpness = variance / (variance + kSharpnessHalf);

  const cv::Rect box = cv::boundingRect(body);
  int edges = 0;
  if (box.x == 0) ++edges;
  if (box.y == 0) ++edges;
  if (box.x + box.width == image.cols) ++edges;
  if (box.y + box.height == image.rows) ++edges;
  // A mask-less image is the whole frame: it touches all edges by construction, so do not count them.
  if (mask.empty()) edges = 0;
  q.completeness = (1.0 - 0.25 * edges) * std::min(1.0, pixels / kFullBodyPixels);
  q.score = q.sharpness * q.completeness;
  return q;
}

}  // namespace bodyrec
