#include "bodyrec/rgbd/ground_plane.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "bodyrec/core/error.h"

namespace bodyrec {

std::optional<GroundPlane> fit_ground_plane(const cv::Mat& depth, const Intrinsics& k, double unit,
                                            const GroundPlaneOptions& o) {
  if (depth.type() != CV_16U || depth.cols != k.width || depth.rows != k.height)
    throw InputError("ground plane: depth must be 16-bit " + std::to_string(k.width) + "x" + std::to_string(k.height));
  // Samples: every 4th pixel of the lower 2/3 of the image (the floor is below the horizon of a
  // roughly level sensor).
  std::vector<cv::Vec3d> pts;
  for (int v = k.height / 3; v < k.height; v += 4) {
    const uint16_t* d = depth.ptr<uint16_t>(v);
    const double ry = (k.cy - v) / k.fy;
    for (int u = 0; u < k.width; u += 4) {
      if (!d[u]) continue;
      const double z = d[u] * unit;
      if (z > o.max_range_m) continue;
      pts.emplace_back(static_cast<float>((u - k.cx) / k.fx) * z, static_cast<float>(ry) * z, z);
    }
  }
  if (pts.size() < 50) return std::nullopt;
  uint64_t state = 0x9e3779b97f4a7c15ULL;  // the same depth image gives the same plane, in any order
  const auto next = [&state] {             // xorshift64*: deterministic, independent of the C library
    state ^= state >> 12;
    state ^= state << 25;
    state ^= state >> 27;
    return state * 2685821657736338717ULL;
  };
  const double tol = o.inlier_m, min_ny = std::cos(o.max_tilt_deg * CV_PI / 180.0);
  cv::Vec4d best;
  size_t best_count = 0;
  for (int it = 0; it < o.iterations; ++it) {
    const cv::Vec3d& a = pts[next() % pts.size()];
    const cv::Vec3d& b = pts[next() % pts.size()];
    const cv::Vec3d& c = pts[next() % pts.size()];
    cv::Vec3d n = (b - a).cross(c - a);
    const double len = cv::norm(n);
    if (len < 1e-9) continue;
    n /= len;
    if (n[1] < 0) n = -n;
    if (n[1] < min_ny) continue;  // not a floor for a roughly level sensor
    const double d = -n.dot(a);
    if (d < o.min_camera_height_m) continue;  // the camera must be above it
    size_t count = 0;
    for (const auto& p : pts) count += std::abs(n.dot(p) + d) < tol;
    if (count > best_count) {
      best_count = count;
      best = {n[0], n[1], n[2], d};
    }
  }
  if (best_count < std::max<size_t>(50, pts.size() / 20)) return std::nullopt;
  // Least-squares refinement: the smallest principal axis of the inliers.
  cv::Vec3d mean(0, 0, 0);
  std::vector<cv::Vec3d> in;
  for (const auto& p : pts)
    if (std::abs(best[0] * p[0] + best[1] * p[1] + best[2] * p[2] + best[3]) < tol) in.push_back(p);
  for (const auto& p : in) mean += p;
  mean /= static_cast<double>(in.size());
  cv::Matx33d cov = cv::Matx33d::zeros();
  for (const auto& p : in) {
    const cv::Vec3d q = p - mean;
    cov += q * q.t();
  }
  cv::Mat evals, evecs;
  cv::eigen(cv::Mat(cov), evals, evecs);
  cv::Vec3d n(evecs.at<double>(2, 0), evecs.at<double>(2, 1), evecs.at<double>(2, 2));
  if (n[1] < 0) n = -n;
  return GroundPlane(n[0], n[1], n[2], -n.dot(mean));
}

const std::optional<GroundPlane>& GroundPlaneTracker::update(int frame_index, const cv::Mat& depth) {
  if (depth.empty() || (tried_ && plane_ && frame_index - fitted_at_ < every_)) return plane_;
  if (auto g = fit_ground_plane(depth, k_, unit_, options_)) plane_ = g;
  fitted_at_ = frame_index;
  tried_ = true;
  return plane_;
}

}  // namespace bodyrec
