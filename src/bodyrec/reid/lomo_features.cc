#include "bodyrec/reid/lomo_features.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/retinex.h"

namespace bodyrec {
namespace {

constexpr int kSiltpBins = 81;  // 4 neighbours, 3 states each
constexpr int kSiltpRadii[] = {3, 5};

int patch_rows(int height, const LomoOptions& o) { return height < o.patch ? 0 : (height - o.patch) / o.stride + 1; }

int total_patch_rows(const LomoOptions& o) {
  int rows = 0, h = o.height;
  for (int s = 0; s < o.scales; ++s, h /= 2) rows += patch_rows(h, o);
  return rows;
}

// Joint HSV (or Lab) bin index per pixel (CV_16U).
cv::Mat colour_codes(const cv::Mat& bgr, int bins, bool lab) {
  cv::Mat hsv;
  cv::cvtColor(bgr, hsv, lab ? cv::COLOR_BGR2Lab : cv::COLOR_BGR2HSV);  // H 0..179, the rest 0..255
  const int hue_range = lab ? 256 : 180;
  cv::Mat codes(bgr.size(), CV_16U);
  for (int y = 0; y < hsv.rows; ++y) {
    const cv::Vec3b* p = hsv.ptr<cv::Vec3b>(y);
    auto* c = codes.ptr<uint16_t>(y);
    for (int x = 0; x < hsv.cols; ++x) {
      const int h = std::min(p[x][0] * bins / hue_range, bins - 1);
      const int s = p[x][1] * bins / 256, v = p[x][2] * bins / 256;
      c[x] = static_cast<uint16_t>((h * bins + s) * bins + v);
    }
  }
  return codes;
}

// SILTP code per pixel (CV_16U): each of 4 neighbours at `radius` is 1 when brighter than (1 + tau) I,
// 2 when darker than (1 - tau) I, else 0; code = sum state_k 3^k. Borders replicate.
cv::Mat siltp_codes(const cv::Mat& gray, int radius, float tau) {
  cv::Mat padded;
  cv::copyMakeBorder(gray, padded, radius, radius, radius, radius, cv::BORDER_REPLICATE);
  cv::Mat codes(gray.size(), CV_16U);
  const int dx[4] = {radius, 0, -radius, 0}, dy[4] = {0, radius, 0, -radius};
  for (int y = 0; y < gray.rows; ++y) {
    auto* c = codes.ptr<uint16_t>(y);
    for (int x = 0; x < gray.cols; ++x) {
      const float centre = padded.at<float>(y + radius, x + radius);
      int code = 0, weight = 1;
      for (int k = 0; k < 4; ++k, weight *= 3) {
        const float n = padded.at<float>(y + radius + dy[k], x + radius + dx[k]);
        if (n > (1 + tau) * centre) code += weight;
        else if (n < (1 - tau) * centre) code += 2 * weight;
      }
      c[x] = static_cast<uint16_t>(code);
    }
  }
  return codes;
}

// For each patch row: histogram of each patch (masked pixels only), element-wise max over the row.
// Appends patch_rows x bins counts to `out`.
void max_pooled_histograms(const cv::Mat& codes, const cv::Mat& mask, int bins, const LomoOptions& o,
                           std::vector<float>& out) {
  const int rows = patch_rows(codes.rows, o);
  const int cols = codes.cols < o.patch ? 0 : (codes.cols - o.patch) / o.stride + 1;
  std::vector<float> patch(bins);
  for (int r = 0; r < rows; ++r) {
    const size_t base = out.size();
    out.resize(base + bins, 0.0f);
    for (int c = 0; c < cols; ++c) {
      std::fill(patch.begin(), patch.end(), 0.0f);
      for (int y = r * o.stride; y < r * o.stride + o.patch; ++y) {
        const auto* code = codes.ptr<uint16_t>(y);
        const uchar* m = mask.ptr<uchar>(y);
        for (int x = c * o.stride; x < c * o.stride + o.patch; ++x)
          if (m[x]) patch[code[x]] += 1.0f;
      }
      for (int b = 0; b < bins; ++b) out[base + b] = std::max(out[base + b], patch[b]);
    }
  }
}

void log_normalise(float* begin, float* end) {
  double norm = 0;
  for (float* p = begin; p != end; ++p) {
    *p = std::log1p(*p);
    norm += double(*p) * *p;
  }
  if (norm <= 0) return;
  const float inv = static_cast<float>(1.0 / std::sqrt(norm));
  for (float* p = begin; p != end; ++p) *p *= inv;
}

}  // namespace

void LomoOptions::check() const {
  if (width < patch || height < patch) throw UsageError("LOMO: image size must be at least one patch");
  if (patch < 1 || stride < 1) throw UsageError("LOMO: patch and stride must be positive");
  if (scales < 1) throw UsageError("LOMO: scales must be >= 1");
  if (hsv_bins < 2 || hsv_bins > 32) throw UsageError("LOMO: hsv_bins must be in 2..32");
  if (siltp_tau <= 0 || siltp_tau >= 1) throw UsageError("LOMO: siltp_tau must be in (0, 1)");
}

int lomo_length(const LomoOptions& o) {
  return total_patch_rows(o) * (o.hsv_bins * o.hsv_bins * o.hsv_bins + 2 * kSiltpBins);
}

std::vector<float> lomo_features(const PersonImage& image, const LomoOptions& o) {
  CV_Assert(!image.bgr.empty() && image.bgr.type() == CV_8UC3);
  CV_Assert(image.mask.empty() || (image.mask.type() == CV_8U && image.mask.size() == image.bgr.size()));
  const cv::Size size(o.width, o.height);
  cv::Mat bgr, mask;
  cv::resize(image.bgr, bgr, size, 0, 0, cv::INTER_AREA);
  if (image.mask.empty()) {
    mask = cv::Mat(size, CV_8U, cv::Scalar(255));
  } else {
    cv::resize(image.mask, mask, size, 0, 0, cv::INTER_NEAREST);
  }
  cv::Mat colour = o.retinex ? multiscale_retinex(bgr, mask) : bgr;
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  gray.convertTo(gray, CV_32F);
  cv::Mat mask_f;
  mask.convertTo(mask_f, CV_32F, 1.0 / 255.0);  // fraction of body pixels, pooled with the image

  const int colour_bins = o.hsv_bins * o.hsv_bins * o.hsv_bins;
  std::vector<float> hsv, texture[2];
  for (int s = 0; s < o.scales; ++s) {
    if (s > 0) {  // 2x2 average pooling
      const cv::Size half(colour.cols / 2, colour.rows / 2);
      cv::resize(colour, colour, half, 0, 0, cv::INTER_AREA);
      cv::resize(gray, gray, half, 0, 0, cv::INTER_AREA);
      cv::resize(mask_f, mask_f, half, 0, 0, cv::INTER_AREA);
    }
    cv::Mat body = mask_f >= 0.5f;
    max_pooled_histograms(colour_codes(colour, o.hsv_bins, o.lab), body, colour_bins, o, hsv);
    for (int k = 0; k < 2; ++k)
      max_pooled_histograms(siltp_codes(gray, kSiltpRadii[k], o.siltp_tau), body, kSiltpBins, o, texture[k]);
  }
  std::vector<float> feature;
  feature.reserve(static_cast<size_t>(lomo_length(o)));
  feature.insert(feature.end(), hsv.begin(), hsv.end());
  feature.insert(feature.end(), texture[0].begin(), texture[0].end());
  feature.insert(feature.end(), texture[1].begin(), texture[1].end());
  log_normalise(feature.data(), feature.data() + hsv.size());
  log_normalise(feature.data() + hsv.size(), feature.data() + feature.size());
  return feature;
}

}  // namespace bodyrec
