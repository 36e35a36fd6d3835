// The Kinect v2 body model: 25 joints in the SDK's order and names, each joint's parent (the bone that
// ends in a joint carries that joint's orientation), and the quaternion helpers the body files need.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace bodyrec {

enum class Joint : int {
  kSpineBase = 0, kSpineMid, kNeck, kHead,
  kShoulderLeft, kElbowLeft, kWristLeft, kHandLeft,
  kShoulderRight, kElbowRight, kWristRight, kHandRight,
  kHipLeft, kKneeLeft, kAnkleLeft, kFootLeft,
  kHipRight, kKneeRight, kAnkleRight, kFootRight,
  kSpineShoulder, kHandTipLeft, kThumbLeft, kHandTipRight, kThumbRight,
};
constexpr int kJointCount = 25;
constexpr int kMaxBodies = 6;  // Kinect v2 tracks up to six bodies; body index values 0..5

inline int idx(Joint j) { return static_cast<int>(j); }

// "SpineBase", "SpineMid", ... as in the Kinect v2 SDK's JointType names.
const std::array<const char*, kJointCount>& joint_names();
// Parent joint in the Kinect hierarchy; SpineBase (the root) has parent -1.
int joint_parent(int joint);
// Joint index of a name; nullopt when unknown.
std::optional<int> joint_from_name(const std::string& name);

// Unit quaternion (w, x, y, z), Kinect's layout.
struct Quaternion {
  double w = 1, x = 0, y = 0, z = 0;
  static Quaternion from_matrix(const cv::Matx33d& r);     // r orthonormal, det +1
  static Quaternion about_y(double radians);
  cv::Matx33d matrix() const;                            // REQUIRES: normalised
  Quaternion operator*(const Quaternion& o) const;
  double norm() const;
};

// Yaw of a body in degrees from its SpineBase orientation, as in the thesis (digest Ch5):
// asin(clamp(2 (w y - z x), -1, 1)) of the normalised quaternion. Range -90..90.
double thesis_yaw_deg(const Quaternion& spine_base);

}  // namespace bodyrec
