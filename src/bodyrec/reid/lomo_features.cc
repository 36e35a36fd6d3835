#include "bodyrec/reid/lomo_features.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/resample.h"
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

// Quantised H, S, V per pixel (CV_8UC3, each 0..bins-1) as LOMO.m: floor(x * bins) with H, S, V in [0, 1]
// (MATLAB's rgb2hsv), the top value falling into the last bin.
cv::Mat quantised_hsv(const cv::Mat& bgr, int bins) {
  cv::Mat f, hsv;
  bgr.convertTo(f, CV_32FC3, 1.0 / 255.0);
  cv::cvtColor(f, hsv, cv::COLOR_BGR2HSV);  // H in degrees [0, 360), S and V in [0, 1]
  cv::Mat q(bgr.size(), CV_8UC3);
  for (int y = 0; y < hsv.rows; ++y) {
    const cv::Vec3f* p = hsv.ptr<cv::Vec3f>(y);
    cv::Vec3b* o = q.ptr<cv::Vec3b>(y);
    for (int x = 0; x < hsv.cols; ++x) {
      const float unit[3] = {p[x][0] / 360.0f, p[x][1], p[x][2]};
      for (int c = 0; c < 3; ++c)
        o[x][c] = static_cast<uchar>(std::clamp(static_cast<int>(std::floor(unit[c] * bins)), 0, bins - 1));
    }
  }
  return q;
}

// Next pyramid level of quantised channels: the floored mean over each 2x2 block of its body pixels
// (of all four when none is body); an odd last row or column is dropped (LOMO.m's ColorPooling).
cv::Mat pool_quantised(const cv::Mat& q, const cv::Mat& body) {
  cv::Mat out(q.rows / 2, q.cols / 2, CV_8UC3);
  for (int y = 0; y < out.rows; ++y)
    for (int x = 0; x < out.cols; ++x) {
      int sum[3] = {0, 0, 0}, all[3] = {0, 0, 0}, n = 0;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const cv::Vec3b v = q.at<cv::Vec3b>(2 * y + dy, 2 * x + dx);
          const bool in = body.at<uchar>(2 * y + dy, 2 * x + dx) != 0;
          n += in;
          for (int c = 0; c < 3; ++c) all[c] += v[c], sum[c] += in ? v[c] : 0;
        }
      for (int c = 0; c < 3; ++c) out.at<cv::Vec3b>(y, x)[c] = static_cast<uchar>(n ? sum[c] / n : all[c] / 4);
    }
  return out;
}

// Mean over each 2x2 block of a CV_32F image, odd last row or column dropped.
cv::Mat pool_mean(const cv::Mat& m) {
  cv::Mat out(m.rows / 2, m.cols / 2, CV_32F);
  for (int y = 0; y < out.rows; ++y) {
    const float* a = m.ptr<float>(2 * y);
    const float* b = m.ptr<float>(2 * y + 1);
    float* o = out.ptr<float>(y);
    for (int x = 0; x < out.cols; ++x) o[x] = 0.25f * (a[2 * x] + a[2 * x + 1] + b[2 * x] + b[2 * x + 1]);
  }
  return out;
}

// Joint bin index per pixel (CV_16U).
cv::Mat joint_codes(const cv::Mat& q, int bins) {
  cv::Mat codes(q.size(), CV_16U);
  for (int y = 0; y < q.rows; ++y) {
    const cv::Vec3b* p = q.ptr<cv::Vec3b>(y);
    auto* c = codes.ptr<uint16_t>(y);
    for (int x = 0; x < q.cols; ++x) c[x] = static_cast<uint16_t>((p[x][2] * bins + p[x][1]) * bins + p[x][0]);
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

// For each patch row: histogram of each patch (body pixels only), element-wise max over the row.
// Appends patch_rows x bins counts to `out`.
void max_pooled_histograms(const cv::Mat& codes, const cv::Mat& body, int bins, const LomoOptions& o,
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
    out.resize(base + static_cast<size_t>(bins), 0.0f);
    for (int c = 0; c < cols; ++c) {
      const int x0 = grid.mirrored ? codes.cols - o.patch - c * o.stride : c * o.stride;
      for (int y = r * o.stride; y < r * o.stride + o.patch; ++y) {
        const auto* code = codes.ptr<uint16_t>(y);
        const uchar* m = body.ptr<uchar>(y);
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

void unit_normalise(std::vector<float>& v) {
  double norm = 0;
  for (float x : v) norm += double(x) * x;
  if (norm <= 0) return;
  const float inv = static_cast<float>(1.0 / std::sqrt(norm));
  for (float& x : v) x *= inv;
}

// Whole-number counts -> log(1 + x) (from a table: counts are at most the pixels of a patch), unit norm.
void log_normalise(std::vector<float>& v, int max_count) {
  std::vector<float> log1p_of(static_cast<size_t>(max_count) + 1);
  for (size_t k = 0; k < log1p_of.size(); ++k) log1p_of[k] = std::log1p(static_cast<float>(k));
  for (float& x : v) x = log1p_of[static_cast<size_t>(x)];
  unit_normalise(v);
}

// views[0]: the image's counts; views[1] (with mirror): the mirror image's. Returns the finished part;
// `own` (if given) receives the image's own finished part.
std::vector<float> finish(std::vector<float> (&views)[2], bool mirror, int max_count, std::vector<float>* own) {
  log_normalise(views[0], max_count);
  if (own) *own = views[0];
  if (!mirror) return std::move(views[0]);
  log_normalise(views[1], max_count);
  for (size_t i = 0; i < views[0].size(); ++i) views[0][i] = 0.5f * (views[0][i] + views[1][i]);
  unit_normalise(views[0]);
  return std::move(views[0]);
}

}  // namespace

void LomoOptions::check() const {
  if (width < patch || height < patch) throw OptionError("LomoOptions", "width", "and height must be at least one patch");
  if (patch < 1 || stride < 1) throw OptionError("LomoOptions", "patch", "and stride must be positive");
  if (scales < 1) throw OptionError("LomoOptions", "scales", "must be >= 1");
  if (hsv_bins < 2 || hsv_bins > 32) throw OptionError("LomoOptions", "hsv_bins", "must be in 2..32");
  if (siltp_tau <= 0 || siltp_tau >= 1) throw OptionError("LomoOptions", "siltp_tau", "must be in (0, 1)");
}

int lomo_colour_length(const LomoOptions& o) { return total_patch_rows(o) * o.hsv_bins * o.hsv_bins * o.hsv_bins; }
int lomo_texture_length(const LomoOptions& o) { return total_patch_rows(o) * kSiltpBins; }
int lomo_length(const LomoOptions& o) { return lomo_colour_length(o) + 2 * lomo_texture_length(o); }

LomoParts lomo_parts(const PersonImage& image, const LomoOptions& o, bool colours_as_seen, bool colours_retinex,
                     bool mirror, LomoParts* unmirrored) {
  CV_Assert(!image.bgr.empty() && image.bgr.type() == CV_8UC3);
  CV_Assert(image.mask.empty() || (image.mask.type() == CV_8U && image.mask.size() == image.bgr.size()));
  const cv::Size size(o.width, o.height);
  const cv::Mat bgr = resample_image(image.bgr, size);
  const cv::Mat mask = image.mask.empty() ? cv::Mat(size, CV_8U, cv::Scalar(255)) : resample_mask(image.mask, size);
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  gray.convertTo(gray, CV_32F);
  cv::Mat mask_f;
  mask.convertTo(mask_f, CV_32F, 1.0 / 255.0);  // fraction of body pixels, pooled with the image
  const bool wanted[2] = {colours_as_seen, colours_retinex};
  cv::Mat quantised[2];
  for (int k = 0; k < 2; ++k)
    if (wanted[k]) quantised[k] = quantised_hsv(k == 0 ? bgr : multiscale_retinex(bgr, mask), o.hsv_bins);

  const int colour_bins = o.hsv_bins * o.hsv_bins * o.hsv_bins;
  static const std::vector<uint16_t> siltp_mirror = mirrored_siltp_codes();
  const int views = mirror ? 2 : 1;
  std::vector<float> colour[2][2], texture[2][2];  // [colour variant or radius][view]
  cv::Mat body = mask_f >= 0.5f;
  for (int s = 0; s < o.scales; ++s) {
    if (s > 0) {
      for (auto& q : quantised)
        if (!q.empty()) q = pool_quantised(q, body);
      gray = pool_mean(gray);
      mask_f = pool_mean(mask_f);
      body = mask_f >= 0.5f;
    }
    cv::Mat siltp[2], codes[2];
    for (int k = 0; k < 2; ++k) {
      siltp[k] = siltp_codes(gray, kSiltpRadii[k], o.siltp_tau);
      if (wanted[k]) codes[k] = joint_codes(quantised[k], o.hsv_bins);
    }
    for (int v = 0; v < views; ++v) {
      for (int k = 0; k < 2; ++k)
        if (wanted[k]) max_pooled_histograms(codes[k], body, colour_bins, o, {v == 1, nullptr}, colour[k][v]);
      for (int k = 0; k < 2; ++k)
        max_pooled_histograms(siltp[k], body, kSiltpBins, o, {v == 1, v == 1 ? siltp_mirror.data() : nullptr},
                              texture[k][v]);
    }
  }
  LomoParts parts;
  const int max_count = o.patch * o.patch;
  const bool both = mirror && unmirrored;
  for (int k = 0; k < 2; ++k) {
    if (wanted[k]) parts.colour[k] = finish(colour[k], mirror, max_count, both ? &unmirrored->colour[k] : nullptr);
    parts.siltp[k] = finish(texture[k], mirror, max_count, both ? &unmirrored->siltp[k] : nullptr);
  }
  return parts;
}

std::vector<float> lomo_features(const PersonImage& image, const LomoOptions& o) {
  LomoParts p = lomo_parts(image, o, !o.retinex, o.retinex, o.mirror);
  std::vector<float> f = std::move(p.colour[o.retinex ? 1 : 0]);
  f.reserve(static_cast<size_t>(lomo_length(o)));
  f.insert(f.end(), p.siltp[0].begin(), p.siltp[0].end());
  f.insert(f.end(), p.siltp[1].begin(), p.siltp[1].end());
  return f;
}

}  // namespace bodyrec
