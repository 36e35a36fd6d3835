#include "bodyrec/reid/body_measures.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "bodyrec/core/error.h"

namespace bodyrec {

void StatureOptions::check() const {
  const auto fail = [](const char* field, const char* problem) { throw OptionError("StatureOptions", field, problem); };
  if (top_rank < 1) fail("top_rank", "must be at least 1");
  if (!(near_body_m > 0)) fail("near_body_m", "must be positive");
  if (!(occluder_m > 0)) fail("occluder_m", "must be positive");
  if (above_px < 1) fail("above_px", "must be at least 1");
  if (!(head_band_m >= 0)) fail("head_band_m", "must not be negative");
  if (!(min_m > 0)) fail("min_m", "must be positive");
  if (!(max_m > min_m)) fail("max_m", "must be above min_m");
}

std::optional<double> measure_stature(const cv::Mat& depth, double unit, const Intrinsics& k, const cv::Mat& labels,
                                      int label, const GroundPlane& ground, const StatureOptions& o,
                                      std::string* why) {
  o.check();
  if (depth.type() != CV_16U || labels.type() != CV_8U || depth.size() != labels.size() || depth.cols != k.width ||
      depth.rows != k.height)
    throw InputError("stature: depth (CV_16U) and labels (CV_8U) must have the depth intrinsics' size");
  const auto fail = [&](const std::string& reason) -> std::optional<double> {
    if (why) *why = reason;
    return std::nullopt;
  };
  struct Px {
    int u, v;
    uint16_t d;
  };
  std::vector<Px> px;
  px.reserve(4096);
  for (int v = 0; v < depth.rows; ++v) {
    const uint8_t* l = labels.ptr<uint8_t>(v);
    const uint16_t* d = depth.ptr<uint16_t>(v);
    for (int u = 0; u < depth.cols; ++u)
      if (l[u] == label && d[u]) px.push_back({u, v, d[u]});
  }
  if (static_cast<int>(px.size()) < std::max(50, 4 * o.top_rank)) return fail("too few body pixels with depth");
  std::vector<uint16_t> ds(px.size());
  for (size_t i = 0; i < px.size(); ++i) ds[i] = px[i].d;
  std::nth_element(ds.begin(), ds.begin() + static_cast<long>(ds.size() / 2), ds.end());
  const double median = ds[ds.size() / 2] * unit;
  // The highest points of the body proper.
  struct Top {
    double h;
    int u, v;
    double z;
  };
  std::vector<Top> top;
  for (const Px& p : px) {
    const double z = p.d * unit;
    if (std::abs(z - median) > o.near_body_m) continue;
    const cv::Vec3d q((p.u - k.cx) / k.fx * z, (k.cy - p.v) / k.fy * z, z);
    top.push_back({height_above(ground, q), p.u, p.v, z});
  }
  if (static_cast<int>(top.size()) < o.top_rank) return fail("too few body pixels near the body's depth");
  const auto higher = [](const Top& a, const Top& b) { return a.h > b.h; };
  std::sort(top.begin(), top.end(), higher);
  const double stature = top[static_cast<size_t>(o.top_rank - 1)].h;
  // The top must be the person's: not cut by the image border, and no nearer surface (someone or
  // something in front) next to the head, the band within head_band_m of the top, where it could hide
  // the top itself.
  const int r = o.above_px;
  for (const Top& t : top) {
    if (t.h < stature - o.head_band_m) break;  // sorted: the rest is lower
    if (t.v < r || t.u < r || t.u >= depth.cols - r) return fail("the body's head is at the image border");
    for (int v = std::max(0, t.v - r); v <= std::min(depth.rows - 1, t.v + r); ++v) {
      const uint16_t* d = depth.ptr<uint16_t>(v);
      const uint8_t* l = labels.ptr<uint8_t>(v);
      for (int u = std::max(0, t.u - r); u <= std::min(depth.cols - 1, t.u + r); ++u)
        if (d[u] && l[u] != label && d[u] * unit < t.z - o.occluder_m) return fail("a nearer surface covers the body's top");
    }
  }
  if (stature < o.min_m || stature > o.max_m) return fail("implausible stature " + std::to_string(stature) + " m");
  return stature;
}

void StatureTrack::add(double stature_m) {
  values_.push_back(stature_m);
  ++count_;
  if (static_cast<int>(values_.size()) > keep_) values_.erase(values_.begin());
}

std::optional<double> StatureTrack::estimate(int last) const {
  if (static_cast<int>(values_.size()) < min_count_ || values_.empty()) return std::nullopt;
  const size_t from = last > 0 && static_cast<size_t>(last) < values_.size() ? values_.size() - static_cast<size_t>(last) : 0;
  std::vector<double> v(values_.begin() + static_cast<long>(from), values_.end());
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(0.75 * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

}  // namespace bodyrec
