#include "bodyrec/reid/orientation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bodyrec {
namespace {

constexpr double kDeg = 180.0 / M_PI;

std::string fmt(const char* format, double a) {
  char buf[160];
  std::snprintf(buf, sizeof buf, format, a);
  return buf;
}

bool in(double v, double lo, double hi) { return v >= lo && v <= hi; }
bool in(const std::optional<double>& v, double lo, double hi) { return v && in(*v, lo, hi); }

}  // namespace

double wrap_deg(double a) {
  double r = std::remainder(a, 360.0);
  if (r <= -180) r += 360;
  return r;
}

double angle_diff_deg(double a, double b) { return std::abs(wrap_deg(a - b)); }

View view_of_yaw(double yaw_deg) {
  const long k = std::lround(wrap_deg(yaw_deg) / 45.0);  // -4..4
  switch (k) {
    case 0: return View::F;
    case -1: return View::FR;
    case -2: return View::SR;
    case -3: return View::BL;
    case 1: return View::FL;
    case 2: return View::SL;
    case 3: return View::BR;
    default: return View::B;
  }
}

double view_yaw_deg(View view) {
  switch (view) {
    case View::F: return 0;
    case View::FR: return -45;
    case View::SR: return -90;
    case View::BL: return -135;
    case View::B: return 180;
    case View::BR: return 135;
    case View::SL: return 90;
    case View::FL: return 45;
  }
  return 0;
}

std::optional<Quaternion> normalised(const Quaternion& q) {
  if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) return std::nullopt;
  const double n = q.norm();
  if (!(n > 1e-9)) return std::nullopt;
  return Quaternion{q.w / n, q.x / n, q.y / n, q.z / n};
}

double thesis_spine_yaw_deg(const Quaternion& q) { return thesis_yaw_deg(q); }  // rgbd/skeleton.h

double thesis_pitch_deg(const Quaternion& q) {
  return std::atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x * q.x + q.y * q.y)) * kDeg;
}

ViewEstimate thesis_view(double yaw, std::optional<double> psr, std::optional<double> psl, std::optional<bool> face) {
  ViewEstimate e;
  e.source = "quaternion";
  const auto found = [&](View v) {
    e.view = v;
    e.confidence = 1;
    // bodyrec yaw implied by the half the rule (or the face) says: front -yaw, back yaw - 180.
    const bool front = v == View::F || v == View::FR || v == View::FL || (face && *face);
    e.yaw_deg = front ? wrap_deg(-yaw) : wrap_deg(yaw - 180);
    e.has_yaw = true;
    return e;
  };
  bool needed_face = false;
  if (in(yaw, -11, 11)) {
    if (face) return found(*face ? View::F : View::B);
    needed_face = true;
  }
  if (in(yaw, 25, 45)) {
    if (face && *face) return found(View::FR);
    needed_face |= !face;
  }
  if (in(yaw, -45, -25)) {
    if (face && *face) return found(View::FL);
    needed_face |= !face;
  }
  if (in(yaw, -23, -12)) {
    if (face && !*face) return found(View::BR);
    needed_face |= !face;
  }
  if (in(yaw, 12, 23)) {
    if (face && !*face) return found(View::BL);
    needed_face |= !face;
  }
  if (in(yaw, -70, -50) || in(psr, -125, -105) || in(psl, 130, 150)) return found(View::SL);
  if (in(yaw, 50, 70) || in(psr, 130, 150) || in(psl, -130, -110)) return found(View::SR);
  const std::string face_text = !face ? "unknown face" : (*face ? "face" : "no face");
  e.reason = needed_face ? fmt("yaw %.1f needs the face flag, which is unknown (no colour image)", yaw)
                         : fmt("yaw %.1f", yaw) + " with " + face_text + " matches no rule of the thesis table";
  if (psr) e.reason += fmt(" (pSR %.1f", *psr) + (psl ? fmt(", pSL %.1f)", *psl) : std::string(")"));
  else if (psl) e.reason += fmt(" (pSL %.1f)", *psl);
  return e;
}

ViewEstimate thesis_view(const Body& body, std::optional<bool> face) {
  const auto& sb = body.joints[static_cast<size_t>(idx(Joint::kSpineBase))].orientation;
  if (!sb) {
    ViewEstimate e;
    e.source = "quaternion";
    e.reason = "SpineBase has no orientation";
    return e;
  }
  const auto q = normalised(*sb);
  if (!q) {
    ViewEstimate e;
    e.source = "quaternion";
    e.reason = "SpineBase quaternion is zero or not finite";
    return e;
  }
  const auto pitch = [&](Joint j) -> std::optional<double> {
    const auto& o = body.joints[static_cast<size_t>(idx(j))].orientation;
    if (!o) return std::nullopt;
    const auto n = normalised(*o);
    if (!n) return std::nullopt;
    return thesis_pitch_deg(*n);
  };
  return thesis_view(thesis_spine_yaw_deg(*q), pitch(Joint::kShoulderRight), pitch(Joint::kShoulderLeft), face);
}

std::optional<double> skeleton_yaw_deg(const Body& body, double* weight) {
  const auto w = [&](Joint j) {
    const int s = body.joints[static_cast<size_t>(idx(j))].tracking_state;
    return s >= 2 ? 1.0 : (s == 1 ? 0.5 : 0.0);
  };
  const auto p = [&](Joint j) { return body.joints[static_cast<size_t>(idx(j))].position; };
  // Body up from the spine when it is tracked (tilted cameras), else camera +Y.
  cv::Vec3d up(0, 1, 0);
  if (w(Joint::kSpineBase) > 0 && w(Joint::kSpineShoulder) > 0) {
    const cv::Vec3d s = p(Joint::kSpineShoulder) - p(Joint::kSpineBase);
    if (cv::norm(s) > 0.15 && s[1] > 0) up = s / cv::norm(s);
  }
  cv::Vec3d right(0, 0, 0);
  double total = 0;
  const auto add = [&](Joint l, Joint r) {
    const double wl = std::min(w(l), w(r));
    if (wl <= 0) return;
    cv::Vec3d d = p(r) - p(l);
    d -= up * d.dot(up);
    const double len = cv::norm(d);
    if (!(len > 0.05)) return;  // a collapsed line says nothing
    right += wl * d;
    total += wl * len;
  };
  add(Joint::kShoulderLeft, Joint::kShoulderRight);
  add(Joint::kHipLeft, Joint::kHipRight);
  if (weight) *weight = total;
  if (total <= 0 || cv::norm(right) < 1e-6) return std::nullopt;
  const cv::Vec3d forward = up.cross(right);
  if (std::hypot(forward[0], forward[2]) < 1e-6) return std::nullopt;
  return std::atan2(-forward[0], -forward[2]) * kDeg;
}

}  // namespace bodyrec
