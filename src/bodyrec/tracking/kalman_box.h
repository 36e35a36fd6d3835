// A constant-velocity Kalman filter on one box: state (cx, cy, w, h) and their per-frame velocities,
// measured as (cx, cy, w, h). Noise is relative to the box height (as in DeepSORT), so the filter behaves
// the same for near and far people.
#pragma once

#include <opencv2/video/tracking.hpp>

#include "bodyrec/core/geometry.h"

namespace bodyrec {

struct KalmanNoise {
  double position = 1.0 / 20;     // process std of cx, cy, w, h per frame, times the box height
  double velocity = 1.0 / 160;    // process std of the velocities per frame, times the box height
  double measurement = 1.0 / 20;  // std of a detection's cx, cy, w, h, times the box height
};

class KalmanBoxFilter {
 public:
  // Starts at `box` with zero velocity and a wide velocity uncertainty.
  KalmanBoxFilter(const Box& box, const KalmanNoise& noise);

  // Advances the state by `frames` frames (>= 1). Width and height stay >= 1 px.
  void predict(int frames);
  // Folds in a measured box.
  void correct(const Box& box);

  Box box() const;
  cv::Point2d velocity() const;  // of the centre, px per frame

 private:
  void set_noise(double height);
  cv::KalmanFilter kf_;
  KalmanNoise noise_;
};

}  // namespace bodyrec
