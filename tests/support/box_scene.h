// Ray-cast depth scenes with known geometry for the RGB-D tests: a Kinect v2 depth camera 1 m above a
// floor (Y = -1), looking level, a back wall at 6 m, and axis-aligned slabs (box people) in between.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/rgbd/camera.h"
#include "bodyrec/rgbd/recording.h"

namespace bodyrec::testing {

struct Slab {  // an axis-aligned box facing the camera: x0..x1, floor-relative y0..y1, at depth z
  double x0, x1, y0, y1, z;
  int label = kNoBody;  // the value its pixels get in render()'s labels
};

// Depth (mm, CV_16U, Kinect v2 size) of the scene; `labels`, when given, gets each slab's label on the
// pixels where it is nearest (kNoBody elsewhere).
inline cv::Mat render(const std::vector<Slab>& slabs, cv::Mat* labels = nullptr) {
  const Intrinsics k = kinect2_depth_intrinsics();
  cv::Mat depth(k.height, k.width, CV_16U);
  if (labels) labels->create(k.height, k.width, CV_8U), labels->setTo(cv::Scalar(kNoBody));
  for (int v = 0; v < k.height; ++v)
    for (int u = 0; u < k.width; ++u) {
      const double rx = (u - k.cx) / k.fx, ry = (k.cy - v) / k.fy;
      double z = 6.0;                                    // back wall
      if (ry < 0) z = std::min(z, -1.0 / ry);            // floor
      int label = kNoBody;
      for (const Slab& s : slabs) {
        const double x = rx * s.z, y = ry * s.z + 1.0;   // height above the floor
        if (s.z < z && x >= s.x0 && x <= s.x1 && y >= s.y0 && y <= s.y1) z = s.z, label = s.label;
      }
      depth.at<uint16_t>(v, u) = static_cast<uint16_t>(std::lround(z * 1000));
      if (labels) labels->at<uint8_t>(v, u) = static_cast<uint8_t>(label);
    }
  return depth;
}

// A box person: 0.5 m wide body up to 1.5 m, a 0.2 m head up to `height`, centred at x.
inline std::vector<Slab> person(double x, double z, double height = 1.75, int label = kNoBody) {
  return {{x - 0.25, x + 0.25, 0.0, 1.5, z, label}, {x - 0.1, x + 0.1, 1.5, height, z, label}};
}

inline std::vector<Slab> operator+(std::vector<Slab> a, const std::vector<Slab>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace bodyrec::testing
