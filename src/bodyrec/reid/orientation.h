// Body orientation and the eight partial-scan views (thesis Ch6).
//
// Yaw convention (bodyrec, the same as the synthetic truth `PersonTruth::yaw_deg`): degrees in
// -180..180, 0 = facing the camera, forward = R_y(yaw) (0, 0, -1) = (-sin yaw, 0, -cos yaw) in camera
// space, so +90 faces -X (towards the image's left, u grows with +X) and +-180 shows the back.
//
// Kinect's SpineBase quaternion has its Z axis along the body's forward direction (checked on the 12 NTU
// RGB+D files: median dot product 0.66-1.00 with the forward vector from shoulders and hips), so a body
// facing the camera holds about R_y(180 deg) and the thesis's yaw asin(2(wy - zx)) equals -yaw on the
// front half and yaw - 180 (wrapped) on the back half. The thesis table therefore reads, in bodyrec yaw:
// FR = -25..-45 (front, turned towards +X), FL = +25..+45, SR = -50..-70, SL = +50..+70, BL = -157..-168
// (back, turned towards +X like FR and SR), BR = +157..+168. The nearest-45-degree sectors of the robust
// estimator keep exactly that handedness:
//     yaw:  0   -45  -90  -135  180  135  90   45
//     view: F   FR   SR   BL    B    BR   SL   FL
#pragma once

#include <optional>
#include <string>

#include "bodyrec/core/view.h"
#include "bodyrec/rgbd/recording.h"

namespace bodyrec {

// One body's orientation in one frame. `view` is nullopt when no view can be given; `reason` then says
// why ("SpineBase quaternion is zero", "yaw 47.0 with face matches no rule of the thesis table", ...).
struct ViewEstimate {
  std::optional<View> view;
  double yaw_deg = 0;       // bodyrec convention (above); meaningful when has_yaw
  bool has_yaw = false;
  double confidence = 0;    // 0..1; 0 when there is no view
  std::string reason;       // empty when a view was found, else why not
  std::string source;       // what the yaw came from: "quaternion", "skeleton", "depth", "track"
};

// ---------------------------------------------------------------------------------------------
// Views from yaw.

// Nearest 45-degree sector of a bodyrec yaw (table above). Any finite yaw; wraps.
View view_of_yaw(double yaw_deg);
// The sector centre of a view in bodyrec yaw (F 0, FR -45, SR -90, BL -135, B 180, BR 135, SL 90, FL 45).
double view_yaw_deg(View view);
// Smallest absolute difference of two angles in degrees (0..180).
double angle_diff_deg(double a_deg, double b_deg);
// Wraps to (-180, 180].
double wrap_deg(double a_deg);

// ---------------------------------------------------------------------------------------------
// The thesis's rule (digest Ch6), exactly.

// Normalised copy; nullopt when the quaternion is zero (norm < 1e-9) or not finite.
std::optional<Quaternion> normalised(const Quaternion& q);
// Thesis yaw of SpineBase, degrees: asin(clamp(2(w*y - z*x), -1, 1)). REQUIRES normalised q.
double thesis_spine_yaw_deg(const Quaternion& q);
// Thesis pitch of a shoulder, degrees: atan2(2(w*x + y*z), 1 - 2(x*x + y*y)). REQUIRES normalised q.
double thesis_pitch_deg(const Quaternion& q);

// The interval table, first matching rule wins, in the digest's order:
//   -11 <= yaw <= 11: F if face else B;  25..45 and face: FR;  -45..-25 and face: FL;
//   -23..-12 and no face: BR;  12..23 and no face: BL;
//   SL if yaw in -70..-50 or pSR in -125..-105 or pSL in 130..150;
//   SR if yaw in 50..70 or pSR in 130..150 or pSL in -130..-110.
// `face` nullopt = unknown (no colour image): rules that need it are skipped and the reason says so.
// `pitch_sr` / `pitch_sl` nullopt when the shoulder has no orientation. Anything else -> no view with
// the reason (the table's gaps: 11..12, 23..25, 45..50, 70..90 and their negatives, and yaw/face
// combinations it does not list, e.g. yaw 15 with a face). The yaw in the result is the bodyrec yaw
// implied by the view's half (front: -yaw, back: yaw - 180 wrapped) when face is known.
ViewEstimate thesis_view(double spine_yaw_deg, std::optional<double> pitch_sr, std::optional<double> pitch_sl,
                         std::optional<bool> face);

// The same from a body's quaternions (SpineBase, ShoulderRight, ShoulderLeft), normalised first. A zero
// or non-finite SpineBase quaternion, or none, gives no view with the reason.
ViewEstimate thesis_view(const Body& body, std::optional<bool> face);

// ---------------------------------------------------------------------------------------------
// Yaw from joint positions (no quaternions): the horizontal right vector of the shoulder and hip lines
// (tracked joints weigh 1, inferred 0.5, untracked 0) and forward = up x right, as the skeleton's own
// left/right say. Returns nullopt when neither line is usable. `weight` receives the summed joint
// weights x horizontal line length (m), a measure of how much the lines can be trusted.
std::optional<double> skeleton_yaw_deg(const Body& body, double* weight = nullptr);

}  // namespace bodyrec
