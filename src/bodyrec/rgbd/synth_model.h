// Internals of the synthetic people (synth.h): looks, posed skeletons and the primitives that dress them.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/rgbd/skeleton.h"

namespace bodyrec::synth {

// Counter-based random numbers: a value is a pure function of (seed, stream, index), so frames can be
// rendered in any order and still be byte-identical.
uint32_t hash32(uint64_t x);
double uniform(uint64_t seed, uint64_t stream, uint64_t index);  // [0, 1)

enum class Material : uint8_t { kSkin, kHead, kTop, kBottom, kShoes, kHat, kBag };

struct Look {
  double height = 1.75, shoulder = 0.40, hips = 0.30, build = 1.0;  // metres; build scales girth
  cv::Vec3f skin, hair, top, top2, bottom, bottom2, shoes, hat, bag;  // BGR 0..255
  int top_pattern = 0;      // 0 plain, 1 horizontal stripes, 2 vertical stripes, 3 checks
  int bottom_pattern = 0;   // 0 plain, 1 side stripes
  bool chest_print = false, long_sleeves = true, shorts = false, long_hair = false;
  bool has_hat = false, backpack = false, shoulder_bag = false;
  std::string top_text, bottom_text;
  std::vector<std::string> accessories;
};

// The look of person `identity` of `people`; different identities of one seed get different top colours.
Look make_look(uint64_t seed, int identity, int people);

struct Pose {
  cv::Vec3d floor_point{0, -1, 3};  // point on the floor under SpineBase, camera space
  double yaw = 0;                   // radians, see synth.h
  double phase = 0;                 // gait phase, radians
  double stride = 0;                // gait amplitude 0 (standing) .. 1 (walking)
};

struct Primitive {
  bool capsule = true;
  cv::Vec3f a, b;    // capsule segment; ellipsoid centre in a
  float r = 0;       // capsule radius; ellipsoid bounding radius
  cv::Matx33f m;     // ellipsoid: maps (p - a) into the unit sphere
  Material material = Material::kSkin;
};

struct PersonModel {
  std::array<cv::Vec3d, kJointCount> joints;
  std::array<std::optional<Quaternion>, kJointCount> orientations;
  std::vector<Primitive> primitives;
  cv::Matx33d body_to_camera;  // R_y(yaw)
  cv::Vec3d origin;            // floor point; body coordinates = R^T (p - origin)
  cv::Vec3d head_centre;       // body coordinates
  cv::Vec3d head_radii;
};

PersonModel build_person(const Look& look, const Pose& pose);

// Shaded colour (BGR 0..255) of a surface point `p` with unit normal `n` (camera space).
cv::Vec3f shade(const Look& look, const PersonModel& model, Material material, const cv::Vec3f& p, const cv::Vec3f& n);

}  // namespace bodyrec::synth
