#include "bodyrec/reid/stripe_features.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// The sum of the squared band distances over `common` bands both show, scaled to compared_bands;
// nullopt below min_common (what stripe_distance and StripeIndex both return).
std::optional<double> scaled(double sum, int common, const StripeOptions& o) {
  if (common < o.min_common) return std::nullopt;
  return sum * o.compared_bands / common;
}

}  // namespace

void StripeOptions::check() const {
  const auto fail = [](const char* field, const char* problem) { throw OptionError("StripeOptions", field, problem); };
  if (bands < 1 || bands > 64) fail("bands", "must be 1..64");
  if (!(band_m > 0)) fail("band_m", "must be positive");
  if (!(assumed_stature_m > 0)) fail("assumed_stature_m", "must be positive");
  if (!(min_band_share >= 0 && min_band_share < 1)) fail("min_band_share", "must be in [0, 1)");
  if (hue_bins < 1 || sat_bins < 1 || val_bins < 1 || hue_bins * sat_bins * val_bins > 4096)
    fail("hue_bins", "and sat_bins, val_bins must be positive, at most 4096 bins per band in all");
  if (min_common < 1 || min_common > bands) fail("min_common", "must be 1..bands");
  if (!(compared_bands > 0)) fail("compared_bands", "must be positive");
}

int stripe_length(const StripeOptions& o) { return o.bands * o.hue_bins * o.sat_bins * o.val_bins; }

std::vector<float> stripe_features(const PersonImage& image, const StripeOptions& o) {
  o.check();
  CV_Assert(image.bgr.type() == CV_8UC3 && !image.bgr.empty());
  CV_Assert(image.mask.empty() || (image.mask.type() == CV_8U && image.mask.size() == image.bgr.size()));
  CV_Assert(image.row_height_m.empty() || static_cast<int>(image.row_height_m.size()) == image.bgr.rows);
  // Full resolution, no resampling: a resized image would blend background into the body's edge.
  const cv::Mat& mask = image.mask;
  cv::Mat hsv;
  cv::cvtColor(image.bgr, hsv, cv::COLOR_BGR2HSV);  // H 0..179
  const int rows = hsv.rows, cols = hsv.cols;
  const int per_band = o.hue_bins * o.sat_bins * o.val_bins;
  std::vector<float> f(static_cast<size_t>(stripe_length(o)), 0.f);
  std::vector<double> sums(static_cast<size_t>(o.bands), 0.0);
  double total = 0;
  for (int y = 0; y < rows; ++y) {
    const double h = image.row_height_m.empty() ? (1.0 - (y + 0.5) / rows) * o.assumed_stature_m
                                                : image.row_height_m[static_cast<size_t>(y)];
    if (!std::isfinite(h)) continue;  // a row of the scan whose height was not measured
    const int band = static_cast<int>(std::floor(h / o.band_m));
    if (band < 0 || band >= o.bands) continue;
    float* hist = f.data() + static_cast<size_t>(band) * per_band;
    const cv::Vec3b* p = hsv.ptr<cv::Vec3b>(y);
    const uint8_t* m = mask.empty() ? nullptr : mask.ptr<uint8_t>(y);
    for (int x = 0; x < cols; ++x) {
      if (m && !m[x]) continue;
      const int hb = std::min(p[x][0] * o.hue_bins / 180, o.hue_bins - 1);
      const int sb = p[x][1] * o.sat_bins / 256, vb = p[x][2] * o.val_bins / 256;
      hist[(hb * o.sat_bins + sb) * o.val_bins + vb] += 1.f;
      sums[static_cast<size_t>(band)] += 1;
      total += 1;
    }
  }
  for (int b = 0; b < o.bands; ++b) {
    float* hist = f.data() + static_cast<size_t>(b) * per_band;
    const double sum = sums[static_cast<size_t>(b)];
    // Too few pixels to say what colours the band has (a sliver at the edge of an occlusion): empty.
    if (sum <= 0 || sum < o.min_band_share * total) {
      std::fill(hist, hist + per_band, 0.f);
      continue;
    }
    // sqrt(p / 2): the squared distance of two bands is then their squared Hellinger distance (0..1).
    for (int i = 0; i < per_band; ++i) hist[i] = static_cast<float>(std::sqrt(hist[i] / sum / 2));
  }
  return f;
}

std::optional<double> stripe_distance(DescriptorView a, DescriptorView b, const StripeOptions& o) {
  const size_t per_band = static_cast<size_t>(o.hue_bins * o.sat_bins * o.val_bins);
  CV_Assert(a.size == static_cast<size_t>(stripe_length(o)) && b.size == a.size);
  // In float, kLanes independent sums: the compiler vectorises this loop (it is most of what a gallery
  // search costs) but would not reorder one running double sum.
  constexpr size_t kLanes = 8;
  double d = 0;
  int common = 0;
  for (size_t s = 0; s < static_cast<size_t>(o.bands); ++s) {
    const float* x = a.data + s * per_band;
    const float* y = b.data + s * per_band;
    float nx[kLanes] = {}, ny[kLanes] = {}, dd[kLanes] = {};
    size_t i = 0;
    for (; i + kLanes <= per_band; i += kLanes)
      for (size_t l = 0; l < kLanes; ++l) {
        nx[l] += x[i + l] * x[i + l];
        ny[l] += y[i + l] * y[i + l];
        const float t = x[i + l] - y[i + l];
        dd[l] += t * t;
      }
    for (; i < per_band; ++i) {
      nx[0] += x[i] * x[i];
      ny[0] += y[i] * y[i];
      dd[0] += (x[i] - y[i]) * (x[i] - y[i]);
    }
    float sx = 0, sy = 0, sd = 0;
    for (size_t l = 0; l < kLanes; ++l) sx += nx[l], sy += ny[l], sd += dd[l];
    if (sx <= 0 || sy <= 0) continue;  // a band one of them does not show
    d += sd;
    ++common;
  }
  return scaled(d, common, o);
}

StripeIndex::StripeIndex(StripeOptions options) : options_(options) { options_.check(); }

StripeIndex::Row StripeIndex::sparse(DescriptorView d, bool keep_bins) const {
  CV_Assert(d.size == static_cast<size_t>(stripe_length(options_)));
  const size_t per_band = static_cast<size_t>(options_.hue_bins * options_.sat_bins * options_.val_bins);
  Row r;
  r.norm.assign(static_cast<size_t>(options_.bands), 0.f);
  if (keep_bins) r.start.reserve(static_cast<size_t>(options_.bands) + 1);
  for (size_t b = 0; b < static_cast<size_t>(options_.bands); ++b) {
    if (keep_bins) r.start.push_back(static_cast<uint32_t>(r.bins.size()));
    for (size_t i = b * per_band; i < (b + 1) * per_band; ++i)
      if (d.data[i] != 0) {
        if (keep_bins) r.bins.push_back({static_cast<uint32_t>(i), d.data[i]});
        r.norm[b] += d.data[i] * d.data[i];
      }
    if (r.norm[b] > 0) r.shown |= uint64_t{1} << b;
  }
  if (keep_bins) r.start.push_back(static_cast<uint32_t>(r.bins.size()));
  return r;
}

void StripeIndex::push_back(DescriptorView d) { rows_.push_back(sparse(d)); }

void StripeIndex::set(size_t row, DescriptorView d) { rows_.at(row) = sparse(d); }

void StripeIndex::swap_remove(size_t row) {
  rows_.at(row) = std::move(rows_.back());
  rows_.pop_back();
}

void StripeIndex::distances(DescriptorView probe, std::vector<std::optional<double>>& out) const {
  const Row p = sparse(probe, false);  // its bands and norms; its bins are read where they lie
  out.assign(rows_.size(), std::nullopt);
  for (size_t k = 0; k < rows_.size(); ++k) {
    const Row& r = rows_[k];
    const uint64_t common = p.shown & r.shown;
    const int n = __builtin_popcountll(common);
    if (n < options_.min_common) continue;  // (scaled() would say so too, after the work)
    // |x - y|^2 = |x|^2 + |y|^2 - 2 x.y over each band both show; x.y over the row's non-zero bins.
    double d = 0;
    for (size_t b = 0; b < static_cast<size_t>(options_.bands); ++b) {
      if (!(common >> b & 1)) continue;
      float dot = 0;
      for (uint32_t i = r.start[b]; i < r.start[b + 1]; ++i) dot += probe.data[r.bins[i].index] * r.bins[i].value;
      d += std::max(0.f, p.norm[b] + r.norm[b] - 2 * dot);
    }
    out[k] = scaled(d, n, options_);
  }
}

}  // namespace bodyrec
