#include "bodyrec/reid/retinex.h"

#include <algorithm>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace bodyrec {
namespace {

// The value below which `fraction` of the masked pixels lie.
float percentile(const cv::Mat& values, const cv::Mat& mask, double fraction) {
  std::vector<float> v;
  v.reserve(values.total());
  for (int y = 0; y < values.rows; ++y) {
    const float* row = values.ptr<float>(y);
    const uchar* m = mask.empty() ? nullptr : mask.ptr<uchar>(y);
    for (int x = 0; x < values.cols; ++x)
      if (!m || m[x]) v.push_back(row[x]);
  }
  if (v.empty()) return 0;
  const size_t i = std::min(v.size() - 1, static_cast<size_t>(fraction * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(i), v.end());
  return v[i];
}

}  // namespace

cv::Mat multiscale_retinex(const cv::Mat& bgr, const cv::Mat& mask) {
  CV_Assert(bgr.type() == CV_8UC3);
  CV_Assert(mask.empty() || (mask.type() == CV_8U && mask.size() == bgr.size()));
  cv::Mat image;
  bgr.convertTo(image, CV_32FC3);
  cv::Mat intensity;  // mean of the channels, + 1 so the logarithm is defined
  cv::transform(image, intensity, cv::Matx13f(1.f / 3, 1.f / 3, 1.f / 3));
  intensity += 1.0f;
  cv::Mat log_intensity, msr = cv::Mat::zeros(bgr.size(), CV_32F);
  cv::log(intensity, log_intensity);
  const double sigmas[] = {5.0, 20.0};
  for (double sigma : sigmas) {
    cv::Mat blurred;
    cv::GaussianBlur(intensity, blurred, cv::Size(), sigma, sigma, cv::BORDER_REFLECT);
    cv::log(blurred, blurred);
    msr += log_intensity - blurred;
  }
  // Stretch between the 1st and 99th percentile to 1..255.
  const float lo = percentile(msr, mask, 0.01), hi = percentile(msr, mask, 0.99);
  const float scale = hi > lo ? 254.0f / (hi - lo) : 0.0f;
  cv::Mat target = (msr - lo) * scale + 1.0f;
  cv::max(target, 1.0f, target);
  cv::min(target, 255.0f, target);
  // Scale each pixel's colour by target / intensity (capped so no channel exceeds 255): the brightness
  // is normalised while hue and saturation are kept (chromaticity-preserving Retinex).
  cv::Mat out(bgr.size(), CV_8UC3);
  for (int y = 0; y < bgr.rows; ++y) {
    const cv::Vec3f* p = image.ptr<cv::Vec3f>(y);
    const float* t = target.ptr<float>(y);
    const float* in = intensity.ptr<float>(y);
    cv::Vec3b* o = out.ptr<cv::Vec3b>(y);
    for (int x = 0; x < bgr.cols; ++x) {
      const float peak = std::max({p[x][0], p[x][1], p[x][2], 1.0f});
      const float gain = std::min(255.0f / peak, t[x] / in[x]);
      for (int c = 0; c < 3; ++c) o[x][c] = cv::saturate_cast<uchar>(p[x][c] * gain);
    }
  }
  return out;
}

}  // namespace bodyrec
