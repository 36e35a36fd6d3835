#include "bodyrec/rgbd/camera.h"

#include <cmath>
#include <string>
#include <vector>

#include "bodyrec/core/error.h"

namespace bodyrec {

void Intrinsics::check(const char* what) const {
  const auto bad = [&](const std::string& field) { throw InputError(std::string(what) + ": " + field); };
  if (width <= 0 || height <= 0) bad("width and height must be positive");
  if (!std::isfinite(fx) || !std::isfinite(fy) || fx <= 0 || fy <= 0) bad("fx and fy must be positive");
  if (!std::isfinite(cx) || !std::isfinite(cy)) bad("cx and cy must be finite");
}

std::optional<cv::Point2d> project(const Intrinsics& k, const cv::Vec3d& p) {
  if (!(p[2] > 0)) return std::nullopt;
  return cv::Point2d(k.cx + k.fx * p[0] / p[2], k.cy - k.fy * p[1] / p[2]);
}

cv::Vec3d unproject(const Intrinsics& k, double u, double v, double z) {
  return {(u - k.cx) * z / k.fx, (k.cy - v) * z / k.fy, z};
}

Intrinsics kinect2_depth_intrinsics() { return {512, 424, 365.5, 365.5, 255.5, 211.5}; }
Intrinsics kinect2_color_intrinsics() { return {1920, 1080, 1060.0, 1060.0, 959.5, 539.5}; }
Extrinsics kinect2_depth_to_color() {
  Extrinsics e;
  e.translation = {0.052, 0.0, 0.0};
  return e;
}

Intrinsics scaled(const Intrinsics& k, int width, int height) {
  const double sx = static_cast<double>(width) / k.width, sy = static_cast<double>(height) / k.height;
  // Pixel centres: a pixel's centre at u maps to (u + 0.5) * s - 0.5.
  return {width, height, k.fx * sx, k.fy * sy, (k.cx + 0.5) * sx - 0.5, (k.cy + 0.5) * sy - 0.5};
}

void map_depth_to_color(const cv::Mat& depth, double depth_unit_m, const Intrinsics& dk, const Intrinsics& ck,
                        const Extrinsics& d2c, cv::Mat& coords) {
  CV_Assert(depth.type() == CV_16U && depth.cols == dk.width && depth.rows == dk.height);
  coords.create(depth.size(), CV_32FC2);
  // Per column and row the ray direction is fixed; precompute (u - cx) / fx and (cy - v) / fy.
  std::vector<double> rx(depth.cols), ry(depth.rows);
  for (int u = 0; u < depth.cols; ++u) rx[u] = (u - dk.cx) / dk.fx;
  for (int v = 0; v < depth.rows; ++v) ry[v] = (dk.cy - v) / dk.fy;
  const cv::Matx33d& r = d2c.rotation;
  const cv::Vec3d& t = d2c.translation;
  for (int v = 0; v < depth.rows; ++v) {
    const uint16_t* d = depth.ptr<uint16_t>(v);
    cv::Vec2f* out = coords.ptr<cv::Vec2f>(v);
    for (int u = 0; u < depth.cols; ++u) {
      if (d[u] == 0) {
        out[u] = {-1.f, -1.f};
        continue;
      }
      const double z = d[u] * depth_unit_m, x = rx[u] * z, y = ry[v] * z;
      const double cxp = r(0, 0) * x + r(0, 1) * y + r(0, 2) * z + t[0];
      const double cyp = r(1, 0) * x + r(1, 1) * y + r(1, 2) * z + t[1];
      const double czp = r(2, 0) * x + r(2, 1) * y + r(2, 2) * z + t[2];
      if (czp <= 0) {
        out[u] = {-1.f, -1.f};
        continue;
      }
      out[u] = {static_cast<float>(ck.cx + ck.fx * cxp / czp), static_cast<float>(ck.cy - ck.fy * cyp / czp)};
    }
  }
}

}  // namespace bodyrec
