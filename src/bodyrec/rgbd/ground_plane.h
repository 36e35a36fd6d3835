// The floor under an RGB-D sensor: a plane fitted by RANSAC to the depth image's lower part, shared by
// the depth-only segmentation (rgbd/segment.h) and the body measurements of re-identification
// (reid/body_measures.h), which measure heights above it.
//
//   if (const auto g = fit_ground_plane(frame.depth, meta.depth, meta.depth_unit_m))
//     const double h = height_above(*g, point);  // metres above the floor
#pragma once

#include <optional>

#include <opencv2/core.hpp>

#include "bodyrec/rgbd/camera.h"

namespace bodyrec {

// A plane a X + b Y + c Z + d = 0 in camera space, (a, b, c) unit and pointing up (b > 0).
using GroundPlane = cv::Vec4d;

struct GroundPlaneOptions {
  double max_range_m = 8.0;   // points farther away are not sampled
  double inlier_m = 0.03;     // RANSAC inlier distance
  double max_tilt_deg = 35;   // the sensor is roughly level: the floor's normal is within this of +Y
  double min_camera_height_m = 0.3;  // the camera is above the floor (excludes ceilings and table tops)
  int iterations = 120;
};

// Samples every 4th pixel of the lower 2/3 of the image, RANSAC (a fixed seed: the same image gives the
// same plane) then a least-squares refinement on the inliers. nullopt when fewer than 50 points or fewer
// than 1/20 of them support any plane. REQUIRES depth CV_16U of the intrinsics' size (InputError).
std::optional<GroundPlane> fit_ground_plane(const cv::Mat& depth, const Intrinsics& depth_k, double depth_unit_m,
                                            const GroundPlaneOptions& options = {});

// The floor over a stream of frames: refitted every `every` frames (a fixed or slowly moving sensor),
// the last good plane kept while a fit fails (people covering the floor), fitted every frame while it
// has none yet.
class GroundPlaneTracker {
 public:
  GroundPlaneTracker(const Intrinsics& depth_k, double depth_unit_m, int every = 10, GroundPlaneOptions options = {})
      : k_(depth_k), unit_(depth_unit_m), every_(every), options_(options) {}
  // The plane for frame `frame_index` (increasing) with depth `depth` (may be empty: no refit).
  const std::optional<GroundPlane>& update(int frame_index, const cv::Mat& depth);
  const std::optional<GroundPlane>& plane() const { return plane_; }

 private:
  Intrinsics k_;
  double unit_;
  int every_;
  GroundPlaneOptions options_;
  std::optional<GroundPlane> plane_;
  int fitted_at_ = 0;
  bool tried_ = false;
};

// Signed distance of a camera-space point above the plane (metres, positive above).
inline double height_above(const GroundPlane& g, const cv::Vec3d& p) {
  return g[0] * p[0] + g[1] * p[1] + g[2] * p[2] + g[3];
}

}  // namespace bodyrec
