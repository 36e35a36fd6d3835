#include "bodyrec/rgbd/green_screen.h"

#include <cmath>

#include "bodyrec/core/error.h"

namespace bodyrec {

BackgroundRemoval::BackgroundRemoval(const RecordingMeta& meta) : meta_(meta) {
  meta_.depth.check("background removal: depth intrinsics");
  meta_.color.check("background removal: colour intrinsics");
  const Intrinsics& k = meta_.depth;
  ray_x_.resize(static_cast<size_t>(k.width));
  ray_y_.resize(static_cast<size_t>(k.height));
  for (int u = 0; u < k.width; ++u) ray_x_[static_cast<size_t>(u)] = static_cast<float>((u - k.cx) / k.fx);
  for (int v = 0; v < k.height; ++v) ray_y_[static_cast<size_t>(v)] = static_cast<float>((k.cy - v) / k.fy);
}

void BackgroundRemoval::apply(const cv::Mat& depth, const cv::Mat& body_index, const cv::Mat& color,
                              std::array<cv::Mat, kMaxBodies>& cutouts) const {
  const Intrinsics &dk = meta_.depth, &ck = meta_.color;
  if (depth.type() != CV_16U || depth.cols != dk.width || depth.rows != dk.height)
    throw InputError("background removal: depth must be 16-bit " + std::to_string(dk.width) + "x" + std::to_string(dk.height));
  if (body_index.type() != CV_8U || body_index.size() != depth.size())
    throw InputError("background removal: body index must be 8-bit of the depth size");
  if (color.type() != CV_8UC3 || color.cols != ck.width || color.rows != ck.height)
    throw InputError("background removal: colour must be 8-bit BGR " + std::to_string(ck.width) + "x" + std::to_string(ck.height));

  // Which slots are present (cheap pass over 217k bytes), so only those images are cleared.
  bool present[kMaxBodies] = {};
  for (int v = 0; v < body_index.rows; ++v) {
    const uint8_t* b = body_index.ptr<uint8_t>(v);
    for (int u = 0; u < body_index.cols; ++u)
      if (b[u] < kMaxBodies) present[b[u]] = true;
  }
  for (int s = 0; s < kMaxBodies; ++s) {
    if (present[s]) {
      cutouts[static_cast<size_t>(s)].create(depth.size(), CV_8UC4);
      cutouts[static_cast<size_t>(s)].setTo(cv::Scalar::all(0));
    } else {
      cutouts[static_cast<size_t>(s)].release();
    }
  }
  const cv::Matx33f r(meta_.depth_to_color.rotation);
  const cv::Vec3f t(meta_.depth_to_color.translation);
  const float unit = static_cast<float>(meta_.depth_unit_m), fx = static_cast<float>(ck.fx), fy = static_cast<float>(ck.fy),
              cx = static_cast<float>(ck.cx), cy = static_cast<float>(ck.cy);
  for (int v = 0; v < depth.rows; ++v) {
    const uint8_t* b = body_index.ptr<uint8_t>(v);
    const uint16_t* d = depth.ptr<uint16_t>(v);
    const float ry = ray_y_[static_cast<size_t>(v)];
    for (int u = 0; u < depth.cols; ++u) {
      if (b[u] >= kMaxBodies || d[u] == 0) continue;
      const float z = d[u] * unit, x = ray_x_[static_cast<size_t>(u)] * z, y = ry * z;
      const float pz = r(2, 0) * x + r(2, 1) * y + r(2, 2) * z + t[2];
      if (pz <= 0) continue;
      const float px = r(0, 0) * x + r(0, 1) * y + r(0, 2) * z + t[0];
      const float py = r(1, 0) * x + r(1, 1) * y + r(1, 2) * z + t[1];
      const int cu = static_cast<int>(std::lround(cx + fx * px / pz)), cv_ = static_cast<int>(std::lround(cy - fy * py / pz));
      if (cu < 0 || cv_ < 0 || cu >= ck.width || cv_ >= ck.height) continue;
      const cv::Vec3b c = color.at<cv::Vec3b>(cv_, cu);
      cutouts[b[u]].at<cv::Vec4b>(v, u) = cv::Vec4b(c[0], c[1], c[2], 255);
    }
  }
}

}  // namespace bodyrec
