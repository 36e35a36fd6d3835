#include "bodyrec/reid/orientation_estimator.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <vector>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

constexpr double kDeg = 180.0 / M_PI;

double cos_deg(double a) { return std::cos(a / kDeg); }

// Mean u and depth of the top `rows_m` metres of a body's pixels, in depth pixels; nullopt when none.
std::optional<cv::Vec3d> top_of_body(const cv::Mat& depth, double unit, const Intrinsics& k, const cv::Mat& labels,
                                     int label, double below_top_m) {
  int top = -1;
  for (int v = 0; v < labels.rows && top < 0; ++v) {
    const uint8_t* l = labels.ptr<uint8_t>(v);
    for (int u = 0; u < labels.cols; ++u)
      if (l[u] == label) {
        top = v;
        break;
      }
  }
  if (top < 0) return std::nullopt;
  // Depth of the top rows gives the scale; then average the head's columns and depths.
  double su = 0, sz = 0;
  int n = 0;
  int rows = 8;
  for (int pass = 0; pass < 2; ++pass) {
    su = sz = 0;
    n = 0;
    for (int v = top; v < std::min(labels.rows, top + rows); ++v) {
      const uint8_t* l = labels.ptr<uint8_t>(v);
      const uint16_t* d = depth.ptr<uint16_t>(v);
      for (int u = 0; u < labels.cols; ++u)
        if (l[u] == label && d[u] > 0) {
          su += u;
          sz += d[u] * unit;
          ++n;
        }
    }
    if (n == 0) return std::nullopt;
    rows = std::max(4, static_cast<int>(below_top_m * k.fy / (sz / n)));
  }
  const double z = sz / n;
  return cv::Vec3d(su / n, top + 0.5 * below_top_m * k.fy / z, z);
}

}  // namespace

const char* view_method_name(ViewMethod method) { return method == ViewMethod::kThesis ? "thesis" : "robust"; }

std::optional<ViewMethod> parse_view_method(const std::string& name) {
  if (name == "robust") return ViewMethod::kRobust;
  if (name == "thesis") return ViewMethod::kThesis;
  return std::nullopt;
}

void OrientationOptions::check() const {
  if (face_every < 1) throw UsageError("orientation options: face_every must be >= 1");
  if (!(turn_gain >= 0 && turn_gain <= 1)) throw UsageError("orientation options: turn_gain must be in 0..1");
  for (double w : {sides_weight, face_weight, no_face_weight, motion_weight, continuity_weight, min_speed_mps, walk_axis_speed_mps, forget_s})
    if (!(w >= 0)) throw UsageError("orientation options: weights, speeds and times must be >= 0");
  if (!(smoothing > 0 && smoothing <= 1)) throw UsageError("orientation options: smoothing must be in (0, 1]");
}

std::optional<DepthAxis> depth_axis(const cv::Mat& depth, double unit, const Intrinsics& k, const cv::Mat& labels,
                                    int label) {
  if (depth.type() != CV_16U || labels.type() != CV_8U || depth.size() != labels.size() ||
      depth.cols != k.width || depth.rows != k.height)
    throw InputError("depth_axis: depth (CV_16U) and labels (CV_8U) must have the depth intrinsics' size");
  std::vector<cv::Vec3f> pts;
  pts.reserve(4096);
  for (int v = 0; v < depth.rows; ++v) {
    const uint8_t* l = labels.ptr<uint8_t>(v);
    const uint16_t* d = depth.ptr<uint16_t>(v);
    for (int u = 0; u < depth.cols; ++u)
      if (l[u] == label && d[u] > 0) {
        const double z = d[u] * unit;
        pts.emplace_back(static_cast<float>((u - k.cx) / k.fx * z), static_cast<float>((k.cy - v) / k.fy * z),
                         static_cast<float>(z));
      }
  }
  if (pts.size() < 200) return std::nullopt;
  // Robust top and bottom (1 % tails) against flying pixels.
  std::vector<float> ys(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) ys[i] = pts[i][1];
  const size_t lo = ys.size() / 100, hi = ys.size() - 1 - ys.size() / 100;
  std::nth_element(ys.begin(), ys.begin() + static_cast<long>(hi), ys.end());
  const double top = ys[hi];
  std::nth_element(ys.begin(), ys.begin() + static_cast<long>(lo), ys.end());
  const double bottom = ys[lo];
  DepthAxis a;
  a.height_m = top - bottom;
  // Torso band from the top (robust to clipped feet): chest and upper arms, 0.30-0.65 m below the top.
  double mx = 0, mz = 0, my = 0;
  int n = 0;
  for (const auto& p : pts) {
    mx += p[0], my += p[1], mz += p[2];
    if (p[1] <= top - 0.30 && p[1] >= top - 0.65) ++n;
  }
  a.centroid = cv::Vec3d(mx, my, mz) / static_cast<double>(pts.size());
  a.points = n;
  if (n < 100) return std::nullopt;
  double cx = 0, cz = 0;
  for (const auto& p : pts)
    if (p[1] <= top - 0.30 && p[1] >= top - 0.65) cx += p[0], cz += p[2];
  cx /= n, cz /= n;
  double sxx = 0, szz = 0, sxz = 0;
  for (const auto& p : pts)
    if (p[1] <= top - 0.30 && p[1] >= top - 0.65) {
      const double dx = p[0] - cx, dz = p[2] - cz;
      sxx += dx * dx, szz += dz * dz, sxz += dx * dz;
    }
  sxx /= n, szz /= n, sxz /= n;
  // Major axis of the visible torso surface = shoulder line; facing = up x right.
  const double phi = 0.5 * std::atan2(2 * sxz, sxx - szz);
  const double dx = std::cos(phi), dz = std::sin(phi);
  a.yaw_deg = std::atan2(-dz, dx) * kDeg;
  const double tr = sxx + szz, det = sxx * szz - sxz * sxz;
  const double l1 = 0.5 * tr + std::sqrt(std::max(0.0, 0.25 * tr * tr - det)), l2 = tr - l1;
  a.quality = l1 > 0 ? std::clamp(1 - l2 / l1, 0.0, 1.0) : 0.0;
  return a;
}

cv::Rect2d head_region(const RecordingMeta& meta, const RgbdFrame& frame, const BodyRef& ref) {
  cv::Vec3d head;
  bool have = false;
  if (ref.body) {
    const BodyJoint& j = ref.body->joints[static_cast<size_t>(idx(Joint::kHead))];
    if (j.tracking_state > 0 && j.position[2] > 0.1) head = j.position, have = true;
  }
  if (!have && !ref.labels.empty() && !frame.depth.empty()) {
    const auto t = top_of_body(frame.depth, meta.depth_unit_m, meta.depth, ref.labels, ref.label, 0.25);
    if (t) head = unproject(meta.depth, (*t)[0], (*t)[1], (*t)[2]), have = true;
  }
  if (!have) return {};
  const auto c = project(meta.color, meta.depth_to_color.apply(head));
  if (!c) return {};
  const double z = meta.depth_to_color.apply(head)[2];
  const double h = meta.color.fy * 0.26 / z, w = meta.color.fx * 0.20 / z;
  return {c->x - w / 2, c->y - h / 2, w, h};
}

struct OrientationEstimator::Track {
  double yaw = 0;
  double rate = 0;    // deg/s, the alpha-beta filter's turning rate
  int since_face = 0;  // frames since the face detector last ran on this track
  double belief = 0;  // accumulated evidence (>= 0) that `yaw`'s half (not yaw + 180) is the right one
  double last_time = -1e9;
  std::deque<std::pair<double, cv::Vec2d>> path;  // time, ground position (X, Z)
};

OrientationEstimator::OrientationEstimator(const RecordingMeta& meta, OrientationOptions options)
    : meta_(meta), options_(std::move(options)) {
  options_.check();
  if (options_.use_faces) faces_ = std::make_unique<FaceDetector>(options_.face_cascade);
}

OrientationEstimator::~OrientationEstimator() = default;

std::optional<bool> OrientationEstimator::face_flag(const RgbdFrame& frame, const BodyRef& ref) {
  last_face_ = {};
  if (!faces_ || frame.color.empty()) return std::nullopt;
  last_face_ = faces_->detect(frame.color, head_region(meta_, frame, ref));
  if (!last_face_.looked) return std::nullopt;
  return last_face_.face;
}

ViewEstimate OrientationEstimator::estimate(const RgbdFrame& frame, const BodyRef& ref, std::optional<bool> known_face) {
  std::optional<bool> face;
  last_face_ = {};
  if (known_face) {
    last_face_ = {true, *known_face, {}};
    face = known_face;
  } else if (options_.method == ViewMethod::kThesis) {
    face = face_flag(frame, ref);
  }
  if (options_.method == ViewMethod::kThesis) {
    if (!ref.body) {
      ViewEstimate e;
      e.source = "quaternion";
      e.reason = "the thesis rule needs a skeleton with joint orientations";
      return e;
    }
    return thesis_view(*ref.body, face);
  }

  // The axis and where the body stands.
  ViewEstimate e;
  double axis_quality = 0, yaw0 = 0;
  bool from_skeleton = false;
  std::optional<cv::Vec2d> ground;
  if (ref.body && options_.use_skeleton) {
    double w = 0;
    if (const auto y = skeleton_yaw_deg(*ref.body, &w)) {
      yaw0 = *y;
      axis_quality = std::min(1.0, w / 0.5);
      from_skeleton = true;
      e.source = "skeleton";
    }
    const cv::Vec3d p = ref.body->joints[0].position;
    ground = cv::Vec2d(p[0], p[2]);
  }
  if (!from_skeleton && !ref.labels.empty() && !frame.depth.empty()) {
    if (const auto a = depth_axis(frame.depth, meta_.depth_unit_m, meta_.depth, ref.labels, ref.label)) {
      yaw0 = a->yaw_deg;
      axis_quality = a->quality;
      e.source = "depth";
      if (!ground) ground = cv::Vec2d(a->centroid[0], a->centroid[2]);
    }
  }
  if (e.source.empty()) {
    e.reason = ref.body ? "the skeleton's shoulders and hips are not tracked" : "too few body pixels with depth";
    return e;
  }

  // Track state: forget stale tracks, keep 0.3 s of ground positions.
  Track& t = tracks_[ref.key];
  const double now = frame.time_s;
  if (now - t.last_time > options_.forget_s || now < t.last_time) t = Track{};
  const bool continuing = t.last_time > -1e8;
  if (ground) {
    t.path.emplace_back(now, *ground);
    while (t.path.size() > 2 && now - t.path.front().first > 0.3) t.path.pop_front();
  }

  // Walking direction over the last 0.3 s (people walk forwards).
  std::optional<double> motion_yaw;
  double speed = 0;
  if (t.path.size() >= 2) {
    const double dt = t.path.back().first - t.path.front().first;
    if (dt >= 0.2) {
      const cv::Vec2d v = (t.path.back().second - t.path.front().second) / dt;
      speed = cv::norm(v);
      if (speed >= options_.min_speed_mps) motion_yaw = std::atan2(-v[0], -v[1]) * kDeg;
    }
  }
  // Depth only: a walking body's direction is a better axis than the torso's visible surface, whose
  // principal axis swings with the arms in side views.
  if (!from_skeleton && motion_yaw && speed >= options_.walk_axis_speed_mps) {
    yaw0 = *motion_yaw;
    axis_quality = std::max(axis_quality, std::min(1.0, speed));
    e.source = "depth+motion";
  }

  // The candidate on the track's side (continuity), then this frame's evidence for it (> 0) against the
  // opposite direction (< 0), accumulated over frames up to a cap so that consistent contrary evidence
  // turns it round within a few frames.
  // The face detector costs most of the time: a track whose facing evidence is saturated asks it only
  // every face_every-th frame.
  if (!known_face && (!continuing || t.belief < options_.continuity_weight || ++t.since_face >= options_.face_every)) {
    face = face_flag(frame, ref);
    t.since_face = 0;
  }
  const bool flipped = continuing && cos_deg(yaw0 - t.yaw) < 0;
  const double a = flipped ? wrap_deg(yaw0 + 180) : yaw0;
  double score = 0;
  if (from_skeleton) score += options_.sides_weight * (flipped ? -1 : 1);
  if (face) {
    if (*face) score += options_.face_weight * cos_deg(a);
    else if (last_face_.looked) score -= options_.no_face_weight * cos_deg(a);
  }
  if (motion_yaw) score += options_.motion_weight * std::min(1.0, speed) * cos_deg(a - *motion_yaw);
  double belief = std::min(options_.continuity_weight, (continuing ? t.belief : 0.0) + score);
  double yaw = a;
  bool turned = false;
  if (belief < 0) {  // the evidence says the other way round: no smoothing across the half turn
    yaw = wrap_deg(a + 180);
    belief = -belief;
    turned = true;
  }
  // Alpha-beta filter on the circle: follows a steady turn without lag, smooths jitter.
  if (continuing && !turned) {
    const double dt = std::max(1e-3, now - t.last_time);
    const double predicted = t.yaw + t.rate * dt;
    const double residual = wrap_deg(yaw - predicted);
    yaw = wrap_deg(predicted + options_.smoothing * residual);
    t.rate += options_.turn_gain * residual / dt;
  } else {
    t.rate = 0;
  }
  t.yaw = yaw;
  t.belief = belief;
  t.last_time = now;

  e.yaw_deg = yaw;
  e.has_yaw = true;
  e.view = view_of_yaw(yaw);
  const double margin = 1 - 0.5 * angle_diff_deg(yaw, view_yaw_deg(*e.view)) / 22.5;
  const double sign = 0.5 + 0.5 * std::tanh(belief / 2);
  e.confidence = std::clamp(axis_quality * sign * margin, 0.0, 1.0);
  return e;
}

}  // namespace bodyrec
