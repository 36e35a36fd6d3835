#include "bodyrec/tracking/floor_tracker.h"

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

TrackerOptions box_options(const FloorTrackerOptions& o) {
  o.check();
  TrackerOptions t;
  t.min_hits = o.min_hits;
  t.max_age = o.max_age;
  t.coast_frames = 0;
  t.min_score = 0;
  t.new_track_score = 0;
  // A footprint's size does not change: the size gate of the second pass is moot.
  t.size_gate = 0;
  return t;
}

}  // namespace

void FloorTrackerOptions::check() const {
  if (!(footprint_m > 0)) throw UsageError("floor tracker: footprint_m must be positive");
  if (max_age < 0) throw UsageError("floor tracker: max_age must not be negative");
  if (min_hits < 1) throw UsageError("floor tracker: min_hits must be at least 1");
}

FloorTracker::FloorTracker(FloorTrackerOptions options) : options_(options), tracker_(box_options(options)) {}

std::vector<int> FloorTracker::update(int frame_index, const std::vector<cv::Vec2d>& where) {
  // Boxes in centimetres: the box filter keeps sizes of at least one unit.
  const double side = 100 * options_.footprint_m;
  std::vector<Detection> footprints;
  for (const cv::Vec2d& p : where) footprints.push_back({Box(100 * p[0] - side / 2, 100 * p[1] - side / 2, side, side), 1.0});
  tracker_.update(frame_index, footprints);
  std::vector<int> ids(where.size(), -1);
  for (const TrackedPerson& t : tracker_.all_tracks())
    if (t.detection >= 0 && t.state == TrackState::kConfirmed) ids[static_cast<size_t>(t.detection)] = t.id;
  return ids;
}

}  // namespace bodyrec
