// Multi-person tracking by detection: one constant-velocity Kalman filter per person, detections
// assigned to the predicted boxes by an optimal (Hungarian) assignment on IoU, then a second pass by
// centre distance for tracks the first pass missed (people who were hidden or moved fast).
//
// Life of a track: a detection nobody claims starts a TENTATIVE track (no id yet); after `min_hits`
// matched detections it becomes CONFIRMED and takes the next id (1, 2, ...; never reused). A tentative
// track that misses one detection round is deleted (most false alarms). A confirmed track that misses
// becomes LOST: it is carried by its prediction and can be re-associated for `max_age` frames after its
// last match, keeping its id through short occlusions; then it is deleted.
//
// Detection need not run on every frame: call update() on frames where it ran and predict_only() on the
// others; tracks are carried by the Kalman prediction in between and misses are counted only in update().
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bodyrec/core/geometry.h"
#include "bodyrec/tracking/kalman_box.h"

namespace bodyrec {

struct TrackerOptions {
  int min_hits = 3;              // matched detections (including the first) to confirm a track
  int max_age = 30;              // frames a confirmed track survives without a match (lost)
  int coast_frames = 1;          // frames a lost track is still reported (state "lost", predicted box)
  double iou_gate = 0.3;         // first pass: least IoU between a detection and a predicted box
  double distance_gate = 0.75;   // second pass: largest centre distance, times the predicted box height
  double size_gate = 0.6;        // second pass: least ratio of the smaller to the larger box height
  // Detections scoring below min_score are ignored. Scores are detector-specific; the defaults suit
  // bodyrec's HOG presets (SVM margins), for which low-margin boxes are mostly clutter and cause swaps.
  double min_score = 0.3;
  // Least detector score to start a track; weaker detections only extend existing tracks (as in
  // ByteTrack: a weak detection next to a track is likely that person, alone it is likely clutter).
  double new_track_score = 0.3;
  KalmanNoise noise;             // Kalman noise, relative to the box height
  // Throws UsageError naming the field when a value is out of range.
  void check() const;
};

enum class TrackState { kTentative, kConfirmed, kLost };

// "tentative", "confirmed" or "lost".
std::string to_string(TrackState state);

struct TrackedPerson {
  int id = -1;                  // -1 while tentative
  Box box;                      // filtered (after a match) or predicted box, in frame pixels
  TrackState state = TrackState::kTentative;
  int hits = 0;                 // detections matched so far
  int frames_since_match = 0;   // 0 on a frame where a detection was matched
  int detection = -1;           // index into update()'s detections matched on this frame, -1 none
};

class MultiTracker {
 public:
  explicit MultiTracker(const TrackerOptions& options = {});  // calls options.check()
  ~MultiTracker();
  MultiTracker(MultiTracker&&) noexcept;
  MultiTracker& operator=(MultiTracker&&) noexcept;

  // A frame on which detection ran. `frame_index` must increase from call to call (gaps allowed: the
  // prediction advances by the difference); throws ProcessingError naming the frame otherwise.
  // ENSURES: returns the tracks to report on this frame: confirmed ones, and lost ones within
  //   `coast_frames` of their last match; sorted by id.
  // `may_start_tracks` false: detections nobody claims are dropped (detections from a search around the
  // existing tracks, which would only duplicate them).
  std::vector<TrackedPerson> update(int frame_index, const std::vector<Detection>& detections,
                                    bool may_start_tracks = true);

  // A frame without detection: every track is carried by its prediction. Returns as update() does.
  std::vector<TrackedPerson> predict_only(int frame_index);

  // Every live track, tentative ones included (for drawing and debugging).
  std::vector<TrackedPerson> all_tracks() const;

 private:
  struct Track;
  void advance_to(int frame_index);
  std::vector<TrackedPerson> report() const;
  static TrackedPerson view(const Track& track);

  TrackerOptions options_;
  std::vector<std::unique_ptr<Track>> tracks_;
  int last_frame_ = 0;
  bool started_ = false;
  int next_id_ = 1;
};

}  // namespace bodyrec
