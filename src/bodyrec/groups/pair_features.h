// Pair features: how two people move relative to each other over a time window. One implementation serves
// the offline evaluation/training (replaying ground-truth trajectories) and the online GroupMembership
// (tracks from the video pipeline), so a model trained on one applies to the other.
#pragma once

#include <array>
#include <bitset>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

namespace bodyrec {

// One observation of a person. Positions in metres; `step` numbers the update that produced it (the two
// people of a pair are compared at the updates where both were seen).
struct PersonSample {
  long step = 0;
  double t = 0;             // seconds
  cv::Point2d position;     // metres
  cv::Point2d velocity;     // m/s, from positions (see PersonHistory::add)
  bool has_velocity = false;
};

// A person's recent samples, oldest first.
class PersonHistory {
 public:
  // Appends a sample; REQUIRES t and step larger than the last sample's. Velocity is the displacement
  // from the latest earlier sample at least `velocity_span_s` back (the first sample if none is), over
  // its time: a short span follows turns, a longer one smooths tracker jitter.
  void add(long step, double t, cv::Point2d position, double velocity_span_s);
  // Drops samples older than t_min, keeping those within the last velocity span before it (for the next
  // velocities); what remains in [t_min, now] is unchanged, so windowed features do not change.
  void drop_before(double t_min);

  const std::deque<PersonSample>& samples() const { return samples_; }
  double first_seen() const { return first_seen_; }  // time of the first sample ever added
  double last_seen() const { return samples_.empty() ? first_seen_ : samples_.back().t; }
  bool empty() const { return samples_.empty(); }

 private:
  std::deque<PersonSample> samples_;
  double first_seen_ = 0;
  double velocity_span_s_ = 0;
  bool seen_ = false;
};

// Features of a pair over one window; names and order in kPairFeatureNames.
constexpr int kPairFeatureCount = 15;
using PairFeatureVector = std::array<double, kPairFeatureCount>;
extern const std::array<const char*, kPairFeatureCount> kPairFeatureNames;
// A subset of the features (bit i: feature i of kPairFeatureNames).
using PairFeatureSet = std::bitset<kPairFeatureCount>;

struct PairFeatures {
  PairFeatureVector values{};
  int samples = 0;               // common samples (with velocities) in the window
  double median_distance = 0;    // metres (also inside `values`, as a log)
  double median_speed_difference = 0;  // m/s, | |va| - |vb| |
  double moving_fraction = 0;    // share of samples where both move faster than 0.3 m/s
};

// Features of a and b over their common samples (same `step`) with has_velocity and t in
// [t_end - window_s, t_end]; window_s may be infinite (the whole common time). Nothing when fewer than
// 2 such samples exist.
std::optional<PairFeatures> pair_features(const PersonHistory& a, const PersonHistory& b, double t_end,
                                          double window_s);

// What a rule needs of a pair's features over its common samples of the last `span_s` seconds (median
// distance, median speed difference, moving fraction), kept up to date one sample at a time: recomputing
// them with pair_features costs time in proportion to the history at every update, which over a pair's
// whole common time grows large. The values are exactly pair_features()'s over the same samples.
class RunningPairStatistics {
 public:
  // Adds the two people's samples of one update (REQUIRES both with velocities and t, the same in both,
  // after the previous call's), then drops the samples older than t - span_s.
  void add(const PersonSample& a, const PersonSample& b, double span_s);
  // As pair_features: nothing with fewer than 2 samples; else samples, median_distance,
  // median_speed_difference, moving_fraction and values[0], values[4], values[8] (the others 0).
  std::optional<PairFeatures> features() const;

 private:
  struct Sample {
    double t, distance, speed_difference;
    bool moving;
  };
  std::deque<Sample> samples_;
  std::vector<double> distances_, speed_differences_;  // sorted
  int moving_ = 0;
};

}  // namespace bodyrec
