// Camera models of an RGB-D sensor: pinhole intrinsics of the depth and colour cameras and the rigid
// transform between them, with the Kinect v2 camera-space convention used throughout bodyrec:
// metres, origin at the depth camera, +Z out of the lens, +Y up, and image column u growing with +X
// (the sensor's mirrored view, as in Kinect v2 and NTU RGB+D skeletons):
//   u = cx + fx * X / Z        v = cy - fy * Y / Z
#pragma once

#include <optional>

#include <opencv2/core.hpp>

namespace bodyrec {

struct Intrinsics {
  int width = 0, height = 0;  // image size in pixels
  double fx = 0, fy = 0;      // focal lengths in pixels
  double cx = 0, cy = 0;      // principal point in pixels
  // Throws InputError naming `what` when sizes or focal lengths are not positive or values not finite.
  void check(const char* what) const;
};

// p_colour = rotation * p_depth + translation (metres, camera-space convention above).
struct Extrinsics {
  cv::Matx33d rotation = cv::Matx33d::eye();
  cv::Vec3d translation{0, 0, 0};
  cv::Vec3d apply(const cv::Vec3d& p) const { return rotation * p + translation; }
};

// Pixel (sub-pixel) of a camera-space point; nullopt when Z <= 0.
std::optional<cv::Point2d> project(const Intrinsics& k, const cv::Vec3d& p);

// Camera-space point at pixel (u, v) with depth Z in metres.
cv::Vec3d unproject(const Intrinsics& k, double u, double v, double z);

// Kinect v2 defaults (typical factory values; real devices differ by a few pixels).
Intrinsics kinect2_depth_intrinsics();   // 512x424
Intrinsics kinect2_color_intrinsics();   // 1920x1080
Extrinsics kinect2_depth_to_color();     // colour camera 5.2 cm beside the depth camera

// Scales intrinsics to another image size (e.g. 1920x1080 -> 960x540).
Intrinsics scaled(const Intrinsics& k, int width, int height);

// For every depth pixel with valid depth (CV_16U, `depth_unit_m` metres per unit, 0 = invalid), the
// colour pixel it maps to (CV_32FC2, (u, v) in colour pixels; (-1, -1) for invalid depth). The colour
// position may lie outside the colour image; callers check bounds.
//   REQUIRES: depth.type() == CV_16U, depth size == depth intrinsics size.
void map_depth_to_color(const cv::Mat& depth, double depth_unit_m, const Intrinsics& depth_k,
                        const Intrinsics& color_k, const Extrinsics& depth_to_color, cv::Mat& color_coords);

}  // namespace bodyrec
