// Re-identification keys for a plain camera's tracks, cut where a track's appearance changes to someone
// else's. A tracker fed by a foreground detector follows blobs, not people: a track lost behind someone
// coasts on its prediction and is matched again to whoever appears there, and two people who cross may
// swap tracks. Online re-identification (online_reid.h) keeps a track's user for as long as the key
// lives, so every frame after such a jump would be given the wrong person.
//
// Per tracker id, the segment keeps the descriptors (AppearanceMatcher::describe) of its last `references`
// clear scans. Each new clear scan is compared with them (the best similarity); below `cut_below` (the
// matcher's threshold minus cut_gap x |threshold|) it is a strike, `strikes` in a row cut the track: the
// body gets a new key (decided afresh, recognised again when it was the same person after all) and the
// references start over from that scan. Scans that are not clear (quality below min_quality: occluded,
// cut by the border, small) neither strike nor teach: a person half hidden looks like someone else.
// The other way round, a tracker that lost someone for a moment starts a new id when they show again: a
// new tracker id whose first clear scan clearly matches (join_gap x |threshold| above the threshold, and
// by `margin` x |threshold| better than any other) a segment unseen for at most join_within frames takes
// over that segment's key and references (the body keeps its user without deciding again); the segment
// it was taken from gets a new key should its tracker id show again.
// Keys: the first segment of tracker id t is t itself; the n-th further one t + n x 2^32.
//
//   TrackSegments segments(matcher);
//   segments.next_frame();   // once per frame, before its keys
//   const uint64_t key = segments.key(track_id, scan ? &*scan : nullptr);
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <vector>

#include "bodyrec/reid/appearance_matcher.h"
#include "bodyrec/reid/partial_scan.h"

namespace bodyrec {

struct TrackSegmentOptions {
  bool enabled = true;       // false: the key is the tracker's id
  double cut_gap = 0.6;      // a strike below threshold - cut_gap x |threshold|
  int strikes = 2;           // strikes in a row that cut the track
  int references = 6;        // clear scans a segment keeps to compare with
  double min_quality = 0.5;  // PartialScan::quality of a clear scan
  int join_within = 30;      // frames a lost segment waits to be joined by a new tracker id; 0 = never
  double join_gap = 0.3;     // a join needs the threshold + join_gap x |threshold|
  double margin = 0.3;       // ... and beating the next segment by margin x |threshold|
  int forget_after = 90;     // frames after which an unseen tracker id is forgotten (tracker ids are not reused)
  void check() const;        // UsageError naming the field
};

class TrackSegments {
 public:
  // `matcher` must outlive this object.
  explicit TrackSegments(const AppearanceMatcher& matcher, const TrackSegmentOptions& options = {});
  // The key of tracker id `track` (< 2^32) for this frame, given this frame's scan of it (null: none).
  uint64_t key(uint64_t track, const PartialScan* scan);
  // Segments cut and joined so far (for reports and tests).
  int cuts() const { return cuts_; }
  int joins() const { return joins_; }
  // A new frame: forgets tracker ids unseen for forget_after frames.
  void next_frame();

 private:
  struct Segment {
    uint64_t key = 0;
    uint64_t cuts = 0;
    int strikes = 0;
    int64_t seen = 0;
    bool joinable = false;  // has had a clear scan and may be taken over
    std::deque<std::vector<float>> references;
  };
  const AppearanceMatcher& matcher_;
  TrackSegmentOptions options_;
  double cut_below_ = 0;
  std::map<uint64_t, Segment> segments_;  // by tracker id
  int64_t frame_ = 0;
  int cuts_ = 0, joins_ = 0;
  // The segment of another tracker id that `d` (a new segment's first clear scan) continues, or null.
  Segment* continued(uint64_t track, const std::vector<float>& d);
};

}  // namespace bodyrec
