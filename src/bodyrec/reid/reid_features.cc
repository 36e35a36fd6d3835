#include "bodyrec/reid/reid_features.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bodyrec {

cv::Mat reid_features(const std::vector<float>& descriptor, std::optional<double> stature, int count) {
  cv::Mat m(1, static_cast<int>(descriptor.size()) + kBodyFeatures, CV_32F);
  float* p = m.ptr<float>();
  std::copy(descriptor.begin(), descriptor.end(), p);
  p[descriptor.size()] = stature ? static_cast<float>(*stature) : std::numeric_limits<float>::quiet_NaN();
  p[descriptor.size() + 1] = static_cast<float>(count);
  return m;
}

DescriptorView appearance_of(const GalleryEntry& e) {
  CV_Assert(e.features.type() == CV_32F && e.features.isContinuous());
  const size_t n = e.features.total();
  return {e.features.ptr<float>(), n >= kBodyFeatures ? n - kBodyFeatures : 0};
}

std::optional<double> stature_of(const GalleryEntry& e) {
  if (e.features.total() < static_cast<size_t>(kBodyFeatures)) return std::nullopt;
  const float s = e.features.ptr<float>()[e.features.total() - kBodyFeatures];
  return std::isfinite(s) ? std::optional<double>(s) : std::nullopt;
}

float stature_count_of(const GalleryEntry& e) {
  if (e.features.total() < static_cast<size_t>(kBodyFeatures)) return 0;
  return e.features.ptr<float>()[e.features.total() - 1];
}

}  // namespace bodyrec
