#include "bodyrec/reid/lomo_features.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

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

// SILTP code of the same pixel in the horizontally mirrored image: the right (k = 0) and left (k = 2)
// neighbours swap places, the ones above and below stay.
std::vector<uint16_t> mirrored_siltp_codes() {
  std::vector<uint16_t> m(kSiltpBins);
  for (int code = 0; code < kSiltpBins; ++code) {
    const int right = code % 3, below = code / 3 % 3, left = code / 9 % 3, above = code / 27;
    m[static_cast<size_t>(code)] = static_cast<uint16_t>(left + 3 * below + 9 * right + 27 * above);
  }
  return m;
}

// Which patches max_pooled_histograms reads: the image's own, or those of its horizontal mirror image,
// whose patch columns count from the right edge and whose codes are `remap[code]` (nullptr: unchanged).
struct PatchGrid {
  bool mirrored = false;
  const uint16_t* remap = nullptr;
};

// For each patch row: histogram of each patch (masked pixels only), element-wise max over the row.
// Appends patch_rows x bins counts to `out`.
void max_pooled_histograms(const cv::Mat& codes, const cv::Mat& mask, int bins, const LomoOptions& o,
                           PatchGrid grid, std::vector<float>& out) {
  const int rows = patch_rows(codes.rows, o);
  const int cols = codes.cols < o.patch ? 0 : (codes.cols - o.patch) / o.stride + 1;
  // A patch has far fewer pixels than bins (100 against 512 by default): only the bins it touched are
  // pooled and cleared.
  std::vector<int> patch(static_cast<size_t>(bins), 0);
  std::vector<int> touched;
  touched.reserve(static_cast<size_t>(o.patch * o.patch));
  for (int r = 0; r < rows; ++r) {
    const size_t base = out.size();
    out.resize(base + bins, 0.0f);
    for (int c = 0; c < cols; ++c) {
      const int x0 = grid.mirrored ? codes.cols - o.patch - c * o.stride : c * o.stride;
      for (int y = r * o.stride; y < r * o.stride + o.patch; ++y) {
        const auto* code = codes.ptr<uint16_t>(y);
        const uchar* m = mask.ptr<uchar>(y);
        for (int x = x0; x < x0 + o.patch; ++x) {
          if (!m[x]) continue;
          const int b = grid.remap ? grid.remap[code[x]] : code[x];
          if (patch[static_cast<size_t>(b)]++ == 0) touched.push_back(b);
        }
      }
      for (int b : touched) {
        float& pooled = out[base + static_cast<size_t>(b)];
        pooled = std::max(pooled, static_cast<float>(patch[static_cast<size_t>(b)]));
        patch[static_cast<size_t>(b)] = 0;
      }
      touched.clear();
    }
  }
}

void unit_normalise(float* begin, float* end) {
  double norm = 0;
  for (float* p = begin; p != end; ++p) norm += double(*p) * *p;
  if (norm <= 0) return;
  const float inv = static_cast<float>(1.0 / std::sqrt(norm));
  for (float* p = begin; p != end; ++p) *p *= inv;
}

// [colour | texture R=3 | texture R=5] counts -> log(1 + x), colour part and texture part each of unit norm.
// The counts are whole numbers up to the pixels of a patch: log(1 + x) comes from a table.
void log_normalise(std::vector<float>& feature, size_t colour_length, int max_count) {
  std::vector<float> log1p_of(static_cast<size_t>(max_count) + 1);
  for (size_t k = 0; k < log1p_of.size(); ++k) log1p_of[k] = std::log1p(static_cast<float>(k));
  for (float& x : feature) x = log1p_of[static_cast<size_t>(x)];
  unit_normalise(feature.data(), feature.data() + colour_length);
  unit_normalise(feature.data() + colour_length, feature.data() + feature.size());
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
  static const std::vector<uint16_t> siltp_mirror = mirrored_siltp_codes();
  // Histograms of the image ([0]) and, with o.mirror, of its mirror image ([1]) from the same codes.
  const int views = o.mirror ? 2 : 1;
  std::vector<float> hsv[2], texture[2][2];
  for (int s = 0; s < o.scales; ++s) {
    if (s > 0) {  // 2x2 average pooling
      const cv::Size half(colour.cols / 2, colour.rows / 2);
      cv::resize(colour, colour, half, 0, 0, cv::INTER_AREA);
      cv::resize(gray, gray, half, 0, 0, cv::INTER_AREA);
      cv::resize(mask_f, mask_f, half, 0, 0, cv::INTER_AREA);
    }
    cv::Mat body = mask_f >= 0.5f;
    const cv::Mat colour_code = colour_codes(colour, o.hsv_bins, o.lab);
    cv::Mat siltp[2];
    for (int k = 0; k < 2; ++k) siltp[k] = siltp_codes(gray, kSiltpRadii[k], o.siltp_tau);
    for (int v = 0; v < views; ++v) {
      max_pooled_histograms(colour_code, body, colour_bins, o, {v == 1, nullptr}, hsv[v]);
      for (int k = 0; k < 2; ++k)
        max_pooled_histograms(siltp[k], body, kSiltpBins, o, {v == 1, v == 1 ? siltp_mirror.data() : nullptr},
                              texture[v][k]);
    }
  }
  std::vector<float> feature[2];
  for (int v = 0; v < views; ++v) {
    feature[v].reserve(static_cast<size_t>(lomo_length(o)));
    feature[v].insert(feature[v].end(), hsv[v].begin(), hsv[v].end());
    feature[v].insert(feature[v].end(), texture[v][0].begin(), texture[v][0].end());
    feature[v].insert(feature[v].end(), texture[v][1].begin(), texture[v][1].end());
    log_normalise(feature[v], hsv[v].size(), o.patch * o.patch);
  }
  if (o.mirror) {
    for (size_t i = 0; i < feature[0].size(); ++i) feature[0][i] = 0.5f * (feature[0][i] + feature[1][i]);
    unit_normalise(feature[0].data(), feature[0].data() + hsv[0].size());
    unit_normalise(feature[0].data() + hsv[0].size(), feature[0].data() + feature[0].size());
  }
  return feature[0];
}

}  // namespace bodyrec
