// Leader direction (thesis Ch4, step 6): dense Farneback optical flow inside the leader's box, the flow
// at the torso centroid averaged over the last `window` frames (25 in the thesis). The thesis's program
// summed the flow from the first frame on and never reset it; here only the window counts, and the
// average restarts when the leader changes or is re-acquired.
#pragma once

#include <deque>
#include <optional>

#include <opencv2/core.hpp>

#include "bodyrec/core/geometry.h"

namespace bodyrec {

struct LeaderDirectionOptions {
  int window = 25;           // frames averaged (thesis: 25)
  double work_height = 96;   // the box region is resized to this height before the flow (speed)
  double torso_y = 0.35;     // torso centroid: this fraction of the box height below its top
  double torso_size = 0.25;  // flow is averaged over a torso patch this fraction of the box wide and tall
  void check() const;
};

struct Direction {
  double degrees = 0;          // 0 = image right, 90 = image up, counter-clockwise, in [0, 360)
  double magnitude = 0;        // pixels per frame, of the averaged flow
  cv::Point2d flow;            // averaged flow (frame pixels per frame; y down)
  cv::Point2d torso;           // torso centroid on the current frame
  int samples = 0;             // frames in the average
};

// Degrees of a flow vector in the convention above.
double flow_degrees(const cv::Point2d& flow);

class LeaderDirection {
 public:
  explicit LeaderDirection(const LeaderDirectionOptions& options = {});  // calls options.check()
  // `previous` and `current` are consecutive grey frames; `box` is the leader's box on `current`.
  // Returns the averaged direction, nullopt when the box is empty or outside the image.
  std::optional<Direction> update(const cv::Mat& previous, const cv::Mat& current, const Box& box);
  void reset() { flows_.clear(); }

 private:
  LeaderDirectionOptions options_;
  std::deque<cv::Point2d> flows_;
};

}  // namespace bodyrec
