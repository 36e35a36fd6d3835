#include "bodyrec/reid/walking_view.h"

#include <algorithm>
#include <cmath>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

constexpr double kDeg = 180.0 / M_PI;

// Slope of y over t (least squares); nullopt when the times do not spread.
std::optional<double> slope(const std::deque<std::pair<double, double>>& samples) {
  const double n = static_cast<double>(samples.size());
  double st = 0, sy = 0;
  for (const auto& [t, y] : samples) st += t, sy += y;
  const double mt = st / n, my = sy / n;
  double stt = 0, sty = 0;
  for (const auto& [t, y] : samples) stt += (t - mt) * (t - mt), sty += (t - mt) * (y - my);
  if (!(stt > 1e-9)) return std::nullopt;
  return sty / stt;
}

// Confidence from how far a yaw is from the border of its 45-degree sector: 1 at the centre, 0 at a border.
double sector_margin(double yaw_deg) {
  return std::clamp((22.5 - angle_diff_deg(yaw_deg, view_yaw_deg(view_of_yaw(yaw_deg)))) / 22.5, 0.0, 1.0);
}

}  // namespace

void WalkingViewOptions::check() const {
  if (!(window_s > 0)) throw OptionError("WalkingViewOptions", "window_s", "must be > 0");
  if (min_samples < 2) throw OptionError("WalkingViewOptions", "min_samples", "must be >= 2");
  if (!(assumed_stature_m > 0)) throw OptionError("WalkingViewOptions", "assumed_stature_m", "must be > 0");
  if (!(focal_ratio > 0)) throw OptionError("WalkingViewOptions", "focal_ratio", "must be > 0");
  if (face_every < 1) throw OptionError("WalkingViewOptions", "face_every", "must be >= 1");
  const std::pair<const char*, double> non_negative[] = {
      {"min_speed_mps", min_speed_mps}, {"hold_s", hold_s}, {"face_weight", face_weight},
      {"no_face_weight", no_face_weight}, {"motion_weight", motion_weight}, {"evidence_cap", evidence_cap},
      {"forget_s", forget_s}};
  for (const auto& [field, value] : non_negative)
    if (!(value >= 0)) throw OptionError("WalkingViewOptions", field, "must be >= 0");
}

WalkingViewEstimator::WalkingViewEstimator(const WalkingViewOptions& options, const ColourGround* ground)
    : options_(options), ground_(ground) {
  options_.check();
  if (options_.use_faces) faces_ = std::make_unique<FaceDetector>(options_.face_cascade);
}

WalkingViewEstimator::~WalkingViewEstimator() = default;

std::optional<cv::Point2d> WalkingViewEstimator::velocity(const Track& t, const cv::Rect& box, int frame_width) const {
  if (static_cast<int>(t.path.size()) < options_.min_samples) return std::nullopt;
  std::deque<std::pair<double, double>> xs, ys;
  for (const auto& [time, p] : t.path) xs.emplace_back(time, p.x), ys.emplace_back(time, p.y);
  const auto vx = slope(xs), vy = slope(ys);
  if (!vx || !vy) return std::nullopt;
  const cv::Point2d foot(box.x + box.width / 2.0, box.br().y);
  if (ground_) {
    // Towards the camera: the ground direction of a step down the image at the feet; across: its
    // perpendicular on the side of a step to the right.
    const double d = std::max(2.0, 0.05 * box.height);
    const cv::Point2d g = ground_->to_ground(foot);
    cv::Point2d towards = ground_->to_ground(foot + cv::Point2d(0, d)) - g;
    cv::Point2d right = ground_->to_ground(foot + cv::Point2d(d, 0)) - g;
    const double nt = std::hypot(towards.x, towards.y);
    if (!(nt > 1e-12)) return std::nullopt;
    towards /= nt;
    right -= towards * right.dot(towards);
    const double nr = std::hypot(right.x, right.y);
    if (!(nr > 1e-12)) return std::nullopt;
    right /= nr;
    const cv::Point2d v(*vx, *vy);
    return cv::Point2d(v.dot(right), v.dot(towards));
  }
  const auto growth = slope(t.heights);
  if (!growth) return std::nullopt;
  const double h = std::max(1, box.height);
  const double across = *vx / h * options_.assumed_stature_m;
  const double towards = *growth * (options_.focal_ratio * frame_width / h) * options_.assumed_stature_m;
  return cv::Point2d(across, towards);
}

ViewEstimate WalkingViewEstimator::estimate(uint64_t track, double time_s, const cv::Rect& box, const cv::Mat& frame,
                                            std::optional<double> head_x) {
  Track& t = tracks_[track];
  if (time_s - t.last_seen > options_.forget_s) t = Track{};
  t.last_seen = time_s;
  const cv::Point2d foot(box.x + box.width / 2.0, box.br().y);
  t.path.emplace_back(time_s, ground_ ? ground_->to_ground(foot) : foot);
  t.heights.emplace_back(time_s, std::log(std::max(1, box.height)));
  while (!t.path.empty() && t.path.front().first < time_s - options_.window_s) t.path.pop_front();
  while (!t.heights.empty() && t.heights.front().first < time_s - options_.window_s) t.heights.pop_front();
  const int width = frame.empty() ? std::max(1, 2 * box.br().x) : frame.cols;
  const std::optional<cv::Point2d> v = velocity(t, box, width);
  const double speed = v ? std::hypot(v->x, v->y) : 0.0;
  const bool walking = v && speed >= options_.min_speed_mps && speed > 0;

  // The face detector, every face_every-th frame of the track.
  last_face_ = {};
  if (faces_ && !frame.empty() && ++t.since_face >= options_.face_every) {
    t.since_face = 0;
    const double h = box.height, x = head_x.value_or(box.x + box.width / 2.0);
    last_face_ = faces_->detect(frame, cv::Rect2d(x - 0.07 * h, box.y - 0.01 * h, 0.14 * h, 0.16 * h));
  }
  // Front/back evidence.
  if (walking) t.evidence += options_.motion_weight * std::min(1.0, speed) * (v->y / speed);
  if (last_face_.looked) t.evidence += last_face_.face ? options_.face_weight : -options_.no_face_weight;
  t.evidence = std::clamp(t.evidence, -options_.evidence_cap, options_.evidence_cap);
  const auto resolved = [&](double yaw) {
    const bool front = std::cos(yaw / kDeg) > 0;
    if ((front && t.evidence < -1) || (!front && t.evidence > 1)) return wrap_deg(180 - yaw);
    return yaw;
  };

  ViewEstimate e;
  if (walking) {
    const double yaw = resolved(wrap_deg(std::atan2(-v->x, v->y) * kDeg));
    t.yaw = yaw;
    t.yaw_time = time_s;
    e.yaw_deg = yaw;
    e.confidence = std::min(1.0, speed / (2 * options_.min_speed_mps)) * (0.5 + 0.5 * sector_margin(yaw));
    e.source = "walking";
  } else if (t.yaw && time_s - t.yaw_time <= options_.hold_s) {
    const double yaw = resolved(*t.yaw);
    e.yaw_deg = yaw;
    const double fade = options_.hold_s > 0 ? 1.0 - (time_s - t.yaw_time) / options_.hold_s : 0.0;
    e.confidence = 0.5 * fade * (0.5 + 0.5 * sector_margin(yaw));
    e.source = "held";
  } else if (last_face_.face) {
    e.yaw_deg = 0;
    e.confidence = 0.4;
    e.source = "face";
  } else {
    e.reason = !v ? "too few positions for a walking direction" : "standing still, no face seen";
    return e;
  }
  e.has_yaw = true;
  e.view = view_of_yaw(e.yaw_deg);
  return e;
}

void WalkingViewEstimator::forget_before(double time_s) {
  for (auto it = tracks_.begin(); it != tracks_.end();)
    it = it->second.last_seen < time_s - options_.forget_s ? tracks_.erase(it) : std::next(it);
}

}  // namespace bodyrec
