// People followed over frames by where they stand on the floor, for sources that find people anew in
// every frame without identities (the depth-only segmentation, rgbd/segment.h). Each person's floor
// position becomes a square footprint box in metres and the box tracker (tracker.h: constant-velocity
// Kalman prediction, optimal assignment, lost tracks re-associated for max_age frames) follows the
// footprints. Two people passing each other keep their ids: their image boxes overlap, their footprints
// (one in front of the other) do not, and one hidden behind the other for a moment is carried by its
// prediction until it shows again. Someone last seen at the image's side who then misses
// `walk_out_frames` frames or more walked out of view: whoever shows on that track afterwards (often the
// next person coming in at the same side) gets a new id.
//
//   FloorTracker tracker;
//   for (each frame i) {
//     std::vector<cv::Vec2d> where = ...;              // (X, Z) camera space, metres, per person
//     const std::vector<int> ids = tracker.update(i, where);   // one id >= 1 per person, stable
//   }
#pragma once

#include <map>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/tracking/tracker.h"

namespace bodyrec {

struct FloorTrackerOptions {
  double footprint_m = 0.6;  // side of a person's footprint box (the second pass reaches 0.75 of it)
  int max_age = 30;          // frames a person unseen keeps their id (1 s at 30 fps)
  int min_hits = 3;          // frames in a row before a person gets an id (flickering fragments do not)
  int walk_out_frames = 2;   // frames missed after touching the image's side that end a person (0 = never)
  void check() const;        // UsageError naming the field
};

class FloorTracker {
 public:
  explicit FloorTracker(FloorTrackerOptions options = {});

  // The people of frame `frame_index` (increasing, gaps allowed) at floor positions `where` (metres,
  // any fixed planar frame, e.g. camera X and Z); `at_side[i]` (empty: none) says person i touches the
  // image's first or last column. ENSURES one entry per position: the person's id (>= 1, no two equal in
  // one frame, never reused), or -1 while the person has not been seen for min_hits frames in a row yet.
  std::vector<int> update(int frame_index, const std::vector<cv::Vec2d>& where, const std::vector<bool>& at_side = {});

 private:
  struct Seen {
    int id = 0;          // the id reported for the box tracker's track
    int frame = 0;       // last frame it was seen
    bool at_side = false;
  };
  FloorTrackerOptions options_;
  MultiTracker tracker_;
  std::map<int, Seen> seen_;  // by the box tracker's id
  int next_id_ = 1;
};

}  // namespace bodyrec
