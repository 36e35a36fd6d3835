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
  const auto fail = [](const char* field, const char* problem) { throw OptionError("FloorTrackerOptions", field, problem); };
  if (!(footprint_m > 0)) fail("footprint_m", "must be positive");
  if (max_age < 0) fail("max_age", "must not be negative");
  if (min_hits < 1) fail("min_hits", "must be at least 1");
  if (walk_out_frames < 0) fail("walk_out_frames", "must not be negative");
}

FloorTracker::FloorTracker(FloorTrackerOptions options) : options_(options), tracker_(box_options(options)) {}

std::vector<int> FloorTracker::update(int frame_index, const std::vector<cv::Vec2d>& where,
                                      const std::vector<bool>& at_side) {
  if (!at_side.empty() && at_side.size() != where.size())
    throw UsageError("floor tracker: at_side must be empty or one flag per position");
  // Boxes in centimetres: the box filter keeps sizes of at least one unit.
  const double side = 100 * options_.footprint_m;
  std::vector<Detection> footprints;
  for (const cv::Vec2d& p : where) footprints.push_back({Box(100 * p[0] - side / 2, 100 * p[1] - side / 2, side, side), 1.0});
  tracker_.update(frame_index, footprints);
  std::vector<int> ids(where.size(), -1);
  for (const TrackedPerson& t : tracker_.all_tracks()) {
    if (t.detection < 0 || t.state != TrackState::kConfirmed) continue;
    const size_t i = static_cast<size_t>(t.detection);
    auto [it, first] = seen_.emplace(t.id, Seen{});
    Seen& s = it->second;
    const bool walked_out = !first && options_.walk_out_frames > 0 && s.at_side &&
                            frame_index - s.frame > options_.walk_out_frames;
    if (first || walked_out) s.id = next_id_++;
    s.frame = frame_index;
    s.at_side = !at_side.empty() && at_side[i];
    ids[i] = s.id;
  }
  // Tracks the box tracker has dropped (beyond max_age) are not needed any more.
  for (auto it = seen_.begin(); it != seen_.end();)
    it = frame_index - it->second.frame > options_.max_age + 1 ? seen_.erase(it) : std::next(it);
  return ids;
}

}  // namespace bodyrec
