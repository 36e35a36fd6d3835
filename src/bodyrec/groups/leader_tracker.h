// Leader tracking (thesis Ch4, step 5) with dlib's correlation_tracker (DSST: separate translation and
// scale filters), made to notice its own failures. The thesis's tracker was started once and never
// checked: on vtest.avi its box drifts to the image border and stays there. Here the tracker is started
// from the leader's track box and:
//  - it is LOST when the correlation peak is weak (peak-to-sidelobe ratio below min_psr), when it
//    disagrees with the leader's detected box for max_disagreement frames in a row, when no detected
//    track has supported its box for max_unsupported frames (a correlation tracker happily locks onto
//    the background where the person was: its peak stays sharp), or when its box leaves the image;
//  - while it is confident it carries the leader through detector misses (the reported box is the DSST
//    box when the leader's track has no detection on this frame);
//  - it is RE-ACQUIRED when the leader's track is detected again (restart on the detected box), or, when
//    the leader's track has ended, by handing the leader role to the confirmed track that overlaps the
//    last reliable leader box (the leader's identity survives a track break).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/core/geometry.h"
#include "bodyrec/tracking/tracker.h"

namespace bodyrec {

struct LeaderTrackerOptions {
  double min_psr = 4.0;          // below this peak-to-sidelobe ratio the tracker is lost (vtest: median 8)
  int max_disagreement = 3;      // frames in a row with IoU < disagree_iou against the leader's detection
  double disagree_iou = 0.3;
  int max_unsupported = 10;      // frames in a row without a detected track on the tracker's box
  double reacquire_iou = 0.3;    // least IoU of a track with the last reliable leader box to take over
  int reacquire_frames = 35;     // frames after the loss during which a take-over may happen (5 s at 7 fps)
  double max_outside = 0.5;      // lost when more than this fraction of the box is outside the image
  void check() const;
};

enum class LeaderState { kNone, kTracking, kLost };
std::string to_string(LeaderState state);  // "none", "tracking", "lost"

struct LeaderStatus {
  int track_id = -1;              // the leader's track id (after a hand-over, the new one)
  LeaderState state = LeaderState::kNone;
  Box box;                        // leader box on this frame (detected, else DSST); empty when lost
  double psr = 0;                 // last peak-to-sidelobe ratio (0 when not tracking)
  bool reacquired = false;        // this frame ended a loss
  std::optional<int> handed_over_from;  // set on the frame the role moved from an ended track
  // On the frame the tracker was lost: "weak peak", "disagrees", "unsupported" or "left image".
  std::string lost_reason;
};

class LeaderTracker {
 public:
  explicit LeaderTracker(const LeaderTrackerOptions& options = {});  // calls options.check()
  ~LeaderTracker();
  LeaderTracker(LeaderTracker&&) noexcept;
  LeaderTracker& operator=(LeaderTracker&&) noexcept;

  // One frame: `grey` is the frame in grey levels, `tracks` the tracker's reported tracks, `leader_id`
  // the role logic's leader (nullopt: none). A changed leader_id restarts the tracker on that track.
  LeaderStatus update(const cv::Mat& grey, const std::vector<TrackedPerson>& tracks, std::optional<int> leader_id);

 private:
  struct Dsst;
  void start(const cv::Mat& grey, const Box& box);
  const TrackedPerson* successor(const std::vector<TrackedPerson>& tracks, const Box& where) const;
  void hand_over(const cv::Mat& grey, const TrackedPerson& to);

  LeaderTrackerOptions options_;
  std::unique_ptr<Dsst> dsst_;
  LeaderStatus status_;
  Box last_good_;
  int disagreement_ = 0, unsupported_ = 0, frames_lost_ = 0;
  int newest_id_seen_ = 0;  // highest track id seen while the leader's track was reported
};

}  // namespace bodyrec
