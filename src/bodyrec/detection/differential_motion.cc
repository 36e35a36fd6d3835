#include "bodyrec/detection/differential_motion.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {

void DifferentialMotionOptions::check() const {
  const auto fail = [](const char* field, const char* problem) { throw OptionError("DifferentialMotionOptions", field, problem); };
  if (threshold < 0 || threshold > 255) fail("threshold", "must be in 0..255");
  if (!(max_deviation > 0)) fail("max_deviation", "must be > 0");
  if (erode < 0 || erode > 15) fail("erode", "must be in 0..15");
  if (!(work_width == 0 || work_width >= 32)) fail("work_width", "must be 0 or >= 32");
}

DifferentialMotion::DifferentialMotion(const DifferentialMotionOptions& options) : options_(options) {
  options_.check();
}

double MotionResult::energy_in(const Box& b) const {
  if (!ready || integral_.empty()) return 0.0;
  const int x0 = std::clamp(static_cast<int>(std::floor(b.x * scale)), 0, mask.cols);
  const int y0 = std::clamp(static_cast<int>(std::floor(b.y * scale)), 0, mask.rows);
  const int x1 = std::clamp(static_cast<int>(std::ceil((b.x + b.width) * scale)), 0, mask.cols);
  const int y1 = std::clamp(static_cast<int>(std::ceil((b.y + b.height) * scale)), 0, mask.rows);
  if (x1 <= x0 || y1 <= y0) return 0.0;
  const int sum = integral_.at<int>(y1, x1) - integral_.at<int>(y0, x1) - integral_.at<int>(y1, x0) +
                  integral_.at<int>(y0, x0);
  return static_cast<double>(sum) / ((x1 - x0) * (y1 - y0));
}

const MotionResult& DifferentialMotion::update(const cv::Mat& frame) {
  cv::Mat grey;
  if (frame.channels() == 1)
    grey = frame;
  else
    cv::cvtColor(frame, grey, cv::COLOR_BGR2GRAY);
  const double f = options_.work_width > 0 ? std::min(1.0, options_.work_width / grey.cols) : 1.0;
  if (f < 1.0) cv::resize(grey, grey, cv::Size(), f, f, cv::INTER_AREA);
  else grey = grey.clone();  // the caller may reuse its buffer
  prev_ = curr_;
  curr_ = next_;
  next_ = grey;

  result_ = MotionResult{};
  result_.scale = f;
  if (prev_.empty() || curr_.empty()) return result_;
  if (prev_.size() != next_.size() || curr_.size() != next_.size())
    throw InputError("motion: frame size changed from " + std::to_string(curr_.cols) + "x" +
                     std::to_string(curr_.rows) + " to " + std::to_string(next_.cols) + "x" +
                     std::to_string(next_.rows) + " (work size)");
  cv::Mat d1, d2;
  cv::absdiff(prev_, next_, d1);
  cv::absdiff(next_, curr_, d2);
  cv::bitwise_and(d1, d2, result_.mask);
  cv::threshold(result_.mask, result_.mask, options_.threshold, 255, cv::THRESH_BINARY);
  if (options_.erode > 0)
    cv::erode(result_.mask, result_.mask,
              cv::getStructuringElement(cv::MORPH_RECT, {options_.erode, options_.erode}));
  cv::Scalar mean, stddev;
  cv::meanStdDev(result_.mask, mean, stddev);
  result_.ready = true;
  result_.deviation = stddev[0];
  result_.pixels = cv::countNonZero(result_.mask);
  cv::Mat ones;
  result_.mask.convertTo(ones, CV_8U, 1.0 / 255);
  cv::integral(ones, result_.integral_, CV_32S);
  if (result_.pixels > 0 && result_.deviation < options_.max_deviation) {
    result_.valid = true;
    const cv::Rect r = cv::boundingRect(result_.mask);
    result_.box = Box(r.x / f, r.y / f, r.width / f, r.height / f);
  }
  return result_;
}

}  // namespace bodyrec
