#include "bodyrec/reid/stripe_features.h"

#include <cmath>
#include <cstdint>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {

void StripeOptions::check() const {
  if (stripes < 1 || stripes > 64) throw UsageError("stripe features: stripes must be 1..64");
  if (hue_bins < 1 || sat_bins < 1 || val_bins < 1 || hue_bins * sat_bins * val_bins > 4096)
    throw UsageError("stripe features: bins must be positive and at most 4096 per stripe");
}

int stripe_length(const StripeOptions& o) { return o.stripes * o.hue_bins * o.sat_bins * o.val_bins; }

std::vector<float> stripe_features(const PersonImage& image, const StripeOptions& o) {
  o.check();
  CV_Assert(image.bgr.type() == CV_8UC3 && !image.bgr.empty());
  CV_Assert(image.mask.empty() || (image.mask.type() == CV_8U && image.mask.size() == image.bgr.size()));
  // Full resolution, no resampling: a resized image would blend background into the body's edge.
  const cv::Mat& mask = image.mask;
  cv::Mat hsv;
  cv::cvtColor(image.bgr, hsv, cv::COLOR_BGR2HSV);  // H 0..179
  const int rows = hsv.rows, cols = hsv.cols;
  const int per_stripe = o.hue_bins * o.sat_bins * o.val_bins;
  std::vector<float> f(static_cast<size_t>(stripe_length(o)), 0.f);
  for (int y = 0; y < rows; ++y) {
    const int stripe = static_cast<int>(static_cast<int64_t>(y) * o.stripes / rows);
    float* h = f.data() + static_cast<size_t>(stripe) * per_stripe;
    const cv::Vec3b* p = hsv.ptr<cv::Vec3b>(y);
    const uint8_t* m = mask.empty() ? nullptr : mask.ptr<uint8_t>(y);
    for (int x = 0; x < cols; ++x) {
      if (m && !m[x]) continue;
      const int hb = std::min(p[x][0] * o.hue_bins / 180, o.hue_bins - 1);
      const int sb = p[x][1] * o.sat_bins / 256, vb = p[x][2] * o.val_bins / 256;
      h[(hb * o.sat_bins + sb) * o.val_bins + vb] += 1.f;
    }
  }
  for (int s = 0; s < o.stripes; ++s) {
    float* h = f.data() + static_cast<size_t>(s) * per_stripe;
    double sum = 0;
    for (int i = 0; i < per_stripe; ++i) sum += h[i];
    if (sum <= 0) continue;
    // sqrt(p / 2): the squared distance of two stripes is then their squared Hellinger distance (0..1).
    for (int i = 0; i < per_stripe; ++i) h[i] = static_cast<float>(std::sqrt(h[i] / sum / 2));
  }
  return f;
}

}  // namespace bodyrec
