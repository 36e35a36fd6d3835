#include "bodyrec/groups/pair_features.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace bodyrec {
namespace {

constexpr double kMovingSpeed = 0.3;  // m/s: slower people have no reliable heading

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + v.size() / 2;
  std::nth_element(v.begin(), mid, v.end());
  if (v.size() % 2) return *mid;
  return 0.5 * (*mid + *std::max_element(v.begin(), mid));
}

double cross(cv::Point2d a, cv::Point2d b) { return a.x * b.y - a.y * b.x; }

// The median of sorted values as median() computes it.
double sorted_median(const std::vector<double>& v) {
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2] + v[n / 2 - 1]);
}

void insert_sorted(std::vector<double>& v, double x) { v.insert(std::upper_bound(v.begin(), v.end(), x), x); }
void erase_sorted(std::vector<double>& v, double x) { v.erase(std::lower_bound(v.begin(), v.end(), x)); }

}  // namespace

const std::array<const char*, kPairFeatureCount> kPairFeatureNames = {
    "log_median_distance", "log_max_distance",   "distance_std",       "median_velocity_difference",
    "median_speed_difference", "relative_velocity_difference", "log_mean_speed", "heading_agreement",
    "moving_fraction",     "side_by_side",       "log_common_duration",
    "distance_change_rate", "moving_x_log_distance", "velocity_difference_x_log_distance",
    "side_by_side_x_log_distance"};

void PersonHistory::add(long step, double t, cv::Point2d position, double velocity_span_s) {
  if (!seen_) {
    first_seen_ = t;
    seen_ = true;
  }
  velocity_span_s_ = velocity_span_s;
  PersonSample s;
  s.step = step;
  s.t = t;
  s.position = position;
  // The latest earlier sample at least a span back, else the oldest one.
  for (auto it = samples_.rbegin(); it != samples_.rend(); ++it) {
    if (t - it->t >= velocity_span_s || std::next(it) == samples_.rend()) {
      if (t > it->t) {
        s.velocity = (position - it->position) / (t - it->t);
        s.has_velocity = true;
      }
      break;
    }
  }
  samples_.push_back(s);
}

void PersonHistory::drop_before(double t_min) {
  const double keep_from = t_min - velocity_span_s_;
  // Keep one sample at or before keep_from so the next velocity still spans the full interval.
  while (samples_.size() >= 2 && samples_[1].t <= keep_from) samples_.pop_front();
}

std::optional<PairFeatures> pair_features(const PersonHistory& a, const PersonHistory& b, double t_end,
                                          double window_s) {
  const double t_begin = std::isinf(window_s) ? -window_s : t_end - window_s;
  std::vector<const PersonSample*> sa, sb;
  auto ia = a.samples().begin(), ib = b.samples().begin();
  while (ia != a.samples().end() && ib != b.samples().end()) {
    if (ia->step < ib->step) {
      ++ia;
    } else if (ib->step < ia->step) {
      ++ib;
    } else {
      if (ia->has_velocity && ib->has_velocity && ia->t >= t_begin && ia->t <= t_end) {
        sa.push_back(&*ia);
        sb.push_back(&*ib);
      }
      ++ia;
      ++ib;
    }
  }
  const size_t n = sa.size();
  if (n < 2) return std::nullopt;

  std::vector<double> dist(n), vel_diff(n), speed_diff(n), rel_diff(n), mean_speed(n), side;
  double heading = 0, moving = 0, sum_d = 0, sum_d2 = 0;
  for (size_t i = 0; i < n; ++i) {
    const cv::Point2d d = sa[i]->position - sb[i]->position;
    const cv::Point2d va = sa[i]->velocity, vb = sb[i]->velocity;
    const double speed_a = cv::norm(va), speed_b = cv::norm(vb);
    dist[i] = cv::norm(d);
    sum_d += dist[i];
    sum_d2 += dist[i] * dist[i];
    vel_diff[i] = cv::norm(va - vb);
    speed_diff[i] = std::abs(speed_a - speed_b);
    mean_speed[i] = 0.5 * (speed_a + speed_b);
    rel_diff[i] = vel_diff[i] / (mean_speed[i] + 0.2);
    if (speed_a > kMovingSpeed && speed_b > kMovingSpeed) {
      heading += va.dot(vb) / (speed_a * speed_b);
      moving += 1;
      const cv::Point2d sum = va + vb;
      const double sum_norm = cv::norm(sum);
      // Share of the separation across the common heading: 1 side by side, 0 one behind the other.
      if (sum_norm > 1e-9) side.push_back(std::abs(cross(d, sum / sum_norm)) / (dist[i] + 0.1));
    }
  }
  const double mean_d = sum_d / n;
  const double duration = sa.back()->t - sa.front()->t;

  PairFeatures f;
  f.samples = static_cast<int>(n);
  f.median_distance = median(dist);
  f.median_speed_difference = median(speed_diff);
  auto& v = f.values;
  v[0] = std::log(f.median_distance + 0.1);
  v[1] = std::log(*std::max_element(dist.begin(), dist.end()) + 0.1);
  v[2] = std::sqrt(std::max(0.0, sum_d2 / n - mean_d * mean_d));
  v[3] = median(vel_diff);
  v[4] = f.median_speed_difference;
  v[5] = median(rel_diff);
  v[6] = std::log(median(mean_speed) + 0.1);
  v[7] = heading / n;
  v[8] = f.moving_fraction = moving / n;
  v[9] = side.empty() ? 0.0 : median(side);
  v[10] = std::log(duration + 0.4);
  v[11] = std::abs(dist.back() - dist.front()) / (duration + 0.4);
  // Interactions a linear model cannot form itself: closeness matters more when walking, side by side.
  v[12] = v[8] * v[0];
  v[13] = v[5] * v[0];
  v[14] = v[9] * v[0];
  return f;
}

}  // namespace bodyrec

namespace bodyrec {

void RunningPairStatistics::add(const PersonSample& a, const PersonSample& b, double span_s) {
  // The same arithmetic as pair_features.
  const double speed_a = cv::norm(a.velocity), speed_b = cv::norm(b.velocity);
  Sample s{a.t, cv::norm(a.position - b.position), std::abs(speed_a - speed_b),
           speed_a > kMovingSpeed && speed_b > kMovingSpeed};
  samples_.push_back(s);
  insert_sorted(distances_, s.distance);
  insert_sorted(speed_differences_, s.speed_difference);
  moving_ += s.moving;
  const double t_begin = a.t - span_s;
  while (!samples_.empty() && !(samples_.front().t >= t_begin)) {
    const Sample& old = samples_.front();
    erase_sorted(distances_, old.distance);
    erase_sorted(speed_differences_, old.speed_difference);
    moving_ -= old.moving;
    samples_.pop_front();
  }
}

std::optional<PairFeatures> RunningPairStatistics::features() const {
  const size_t n = samples_.size();
  if (n < 2) return std::nullopt;
  PairFeatures f;
  f.samples = static_cast<int>(n);
  f.median_distance = sorted_median(distances_);
  f.median_speed_difference = sorted_median(speed_differences_);
  f.values[0] = std::log(f.median_distance + 0.1);
  f.values[4] = f.median_speed_difference;
  f.values[8] = f.moving_fraction = static_cast<double>(moving_) / n;
  return f;
}

}  // namespace bodyrec
