#include "bodyrec/rgbd/skeleton.h"

#include <algorithm>
#include <cmath>

namespace bodyrec {

const std::array<const char*, kJointCount>& joint_names() {
  static const std::array<const char*, kJointCount> names = {
      "SpineBase",     "SpineMid",  "Neck",       "Head",         "ShoulderLeft",  "ElbowLeft",
      "WristLeft",     "HandLeft",  "ShoulderRight", "ElbowRight", "WristRight",    "HandRight",
      "HipLeft",       "KneeLeft",  "AnkleLeft",  "FootLeft",     "HipRight",      "KneeRight",
      "AnkleRight",    "FootRight", "SpineShoulder", "HandTipLeft", "ThumbLeft",   "HandTipRight",
      "ThumbRight"};
  return names;
}

int joint_parent(int joint) {
  static const std::array<int, kJointCount> parents = {
      -1, 0, 20, 2,      // SpineBase, SpineMid, Neck, Head
      20, 4, 5, 6,       // left arm
      20, 8, 9, 10,      // right arm
      0, 12, 13, 14,     // left leg
      0, 16, 17, 18,     // right leg
      1, 7, 6, 11, 10};  // SpineShoulder, HandTipLeft, ThumbLeft, HandTipRight, ThumbRight
  return parents.at(static_cast<size_t>(joint));
}

std::optional<int> joint_from_name(const std::string& name) {
  const auto& names = joint_names();
  for (int i = 0; i < kJointCount; ++i)
    if (name == names[static_cast<size_t>(i)]) return i;
  return std::nullopt;
}

Quaternion Quaternion::from_matrix(const cv::Matx33d& m) {
  Quaternion q;
  const double trace = m(0, 0) + m(1, 1) + m(2, 2);
  if (trace > 0) {
    const double s = std::sqrt(trace + 1.0) * 2;
    q = {0.25 * s, (m(2, 1) - m(1, 2)) / s, (m(0, 2) - m(2, 0)) / s, (m(1, 0) - m(0, 1)) / s};
  } else if (m(0, 0) > m(1, 1) && m(0, 0) > m(2, 2)) {
    const double s = std::sqrt(1.0 + m(0, 0) - m(1, 1) - m(2, 2)) * 2;
    q = {(m(2, 1) - m(1, 2)) / s, 0.25 * s, (m(0, 1) + m(1, 0)) / s, (m(0, 2) + m(2, 0)) / s};
  } else if (m(1, 1) > m(2, 2)) {
    const double s = std::sqrt(1.0 + m(1, 1) - m(0, 0) - m(2, 2)) * 2;
    q = {(m(0, 2) - m(2, 0)) / s, (m(0, 1) + m(1, 0)) / s, 0.25 * s, (m(1, 2) + m(2, 1)) / s};
  } else {
    const double s = std::sqrt(1.0 + m(2, 2) - m(0, 0) - m(1, 1)) * 2;
    q = {(m(1, 0) - m(0, 1)) / s, (m(0, 2) + m(2, 0)) / s, (m(1, 2) + m(2, 1)) / s, 0.25 * s};
  }
  if (q.w < 0) q = {-q.w, -q.x, -q.y, -q.z};  // one canonical sign
  return q;
}

Quaternion Quaternion::about_y(double a) { return {std::cos(a / 2), 0, std::sin(a / 2), 0}; }

cv::Matx33d Quaternion::matrix() const {
  return {1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
          2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
          2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
}

Quaternion Quaternion::operator*(const Quaternion& o) const {
  return {w * o.w - x * o.x - y * o.y - z * o.z, w * o.x + x * o.w + y * o.z - z * o.y,
          w * o.y - x * o.z + y * o.w + z * o.x, w * o.z + x * o.y - y * o.x + z * o.w};
}

double Quaternion::norm() const { return std::sqrt(w * w + x * x + y * y + z * z); }

double thesis_yaw_deg(const Quaternion& q) {
  const double n = q.norm();
  const double s = 2 * (q.w * q.y - q.z * q.x) / (n * n);
  return std::asin(std::clamp(s, -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace bodyrec
