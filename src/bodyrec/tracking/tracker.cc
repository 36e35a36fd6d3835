#include "bodyrec/tracking/tracker.h"

#include <algorithm>
#include <cmath>

#include "bodyrec/core/error.h"
#include "bodyrec/tracking/assignment.h"

namespace bodyrec {

struct MultiTracker::Track {
  Track(const Box& box, const KalmanNoise& noise) : filter(box, noise) {}
  KalmanBoxFilter filter;
  int id = -1;
  TrackState state = TrackState::kTentative;
  int hits = 1;
  int frames_since_match = 0;
  int detection = -1;  // index into the caller's detections matched on the last update, -1 none
};

void TrackerOptions::check() const {
  const auto fail = [](const char* field, const char* problem) { throw OptionError("TrackerOptions", field, problem); };
  if (min_hits < 1) fail("min_hits", "must be >= 1");
  if (max_age < 0) fail("max_age", "must be >= 0");
  if (coast_frames < 0) fail("coast_frames", "must be >= 0");
  if (!(iou_gate > 0 && iou_gate <= 1)) fail("iou_gate", "must be in (0, 1]");
  if (!(distance_gate >= 0)) fail("distance_gate", "must be >= 0");
  if (!(size_gate >= 0 && size_gate <= 1)) fail("size_gate", "must be in [0, 1]");
  if (!(noise.position > 0 && noise.velocity > 0 && noise.measurement > 0)) fail("noise", "weights must be > 0");
}

std::string to_string(TrackState state) {
  switch (state) {
    case TrackState::kTentative: return "tentative";
    case TrackState::kConfirmed: return "confirmed";
    case TrackState::kLost: return "lost";
  }
  return "unknown";
}

MultiTracker::MultiTracker(const TrackerOptions& options) : options_(options) { options_.check(); }
MultiTracker::~MultiTracker() = default;
MultiTracker::MultiTracker(MultiTracker&&) noexcept = default;
MultiTracker& MultiTracker::operator=(MultiTracker&&) noexcept = default;

void MultiTracker::advance_to(int frame_index) {
  if (started_ && frame_index <= last_frame_)
    throw ProcessingError("tracker: frame " + std::to_string(frame_index) + " does not follow frame " +
                          std::to_string(last_frame_));
  const int step = started_ ? frame_index - last_frame_ : 0;
  started_ = true;
  last_frame_ = frame_index;
  if (step == 0) return;
  for (auto& t : tracks_) {
    t->filter.predict(step);
    t->frames_since_match += step;
  }
  // Lost tracks too old to be re-associated are deleted.
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [&](const auto& t) { return t->frames_since_match > options_.max_age; }),
                tracks_.end());
}

std::vector<TrackedPerson> MultiTracker::update(int frame_index, const std::vector<Detection>& all_detections,
                                                bool may_start_tracks) {
  advance_to(frame_index);
  std::vector<Detection> detections;
  std::vector<int> original;  // index of each kept detection in all_detections
  for (size_t i = 0; i < all_detections.size(); ++i)
    if (all_detections[i].score >= options_.min_score) {
      detections.push_back(all_detections[i]);
      original.push_back(static_cast<int>(i));
    }
  for (auto& t : tracks_) t->detection = -1;
  const int n_tracks = static_cast<int>(tracks_.size()), n_dets = static_cast<int>(detections.size());
  std::vector<Box> predicted(n_tracks);
  for (int t = 0; t < n_tracks; ++t) predicted[t] = tracks_[t]->filter.box();
  std::vector<int> match_of_track(n_tracks, -1);
  std::vector<bool> det_used(n_dets, false);

  // Pass 1: every track against every detection by IoU with the predicted box.
  std::vector<std::vector<double>> overlap(n_tracks, std::vector<double>(n_dets, 0.0));
  for (int t = 0; t < n_tracks; ++t)
    for (int d = 0; d < n_dets; ++d) overlap[t][d] = iou(predicted[t], detections[d].box);
  for (const auto& [t, d] : max_score_assignment(overlap, options_.iou_gate)) {
    match_of_track[t] = d;
    det_used[d] = true;
  }

  // Pass 2: confirmed and lost tracks left over, by centre distance relative to the predicted height
  // (an occluded or fast person's prediction often overlaps the detection too little for pass 1).
  std::vector<int> rest_tracks, rest_dets;
  for (int t = 0; t < n_tracks; ++t)
    if (match_of_track[t] < 0 && tracks_[t]->state != TrackState::kTentative) rest_tracks.push_back(t);
  for (int d = 0; d < n_dets; ++d)
    if (!det_used[d]) rest_dets.push_back(d);
  if (!rest_tracks.empty() && !rest_dets.empty() && options_.distance_gate > 0) {
    std::vector<std::vector<double>> closeness(rest_tracks.size(), std::vector<double>(rest_dets.size(), 0.0));
    for (size_t i = 0; i < rest_tracks.size(); ++i) {
      const Box& p = predicted[rest_tracks[i]];
      for (size_t j = 0; j < rest_dets.size(); ++j) {
        const Box& b = detections[rest_dets[j]].box;
        const double size_ratio = std::min(p.height, b.height) / std::max({p.height, b.height, 1e-9});
        if (size_ratio < options_.size_gate) continue;
        const double dist = std::hypot(p.x + p.width / 2 - b.x - b.width / 2, p.y + p.height / 2 - b.y - b.height / 2);
        const double reach = options_.distance_gate * p.height;
        if (dist < reach) closeness[i][j] = 1.0 - dist / reach;
      }
    }
    for (const auto& [i, j] : max_score_assignment(closeness, 1e-6)) {
      match_of_track[rest_tracks[i]] = rest_dets[j];
      det_used[rest_dets[j]] = true;
    }
  }

  // Apply the matches and the state transitions.
  for (int t = 0; t < n_tracks; ++t) {
    Track& track = *tracks_[t];
    if (match_of_track[t] >= 0) {
      track.filter.correct(detections[match_of_track[t]].box);
      track.detection = original[static_cast<size_t>(match_of_track[t])];
      ++track.hits;
      track.frames_since_match = 0;
      if (track.state == TrackState::kLost) track.state = TrackState::kConfirmed;
      if (track.state == TrackState::kTentative && track.hits >= options_.min_hits) {
        track.state = TrackState::kConfirmed;
        track.id = next_id_++;
      }
    } else if (track.state == TrackState::kConfirmed) {
      track.state = TrackState::kLost;
    }
  }
  // A tentative track that missed is most likely a false alarm.
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [](const auto& t) {
                                 return t->state == TrackState::kTentative && t->frames_since_match > 0;
                               }),
                tracks_.end());
  for (int d = 0; d < n_dets; ++d) {
    if (!may_start_tracks || det_used[d] || detections[d].score < options_.new_track_score) continue;
    auto track = std::make_unique<Track>(detections[d].box, options_.noise);
    track->detection = original[static_cast<size_t>(d)];
    if (options_.min_hits <= 1) {
      track->state = TrackState::kConfirmed;
      track->id = next_id_++;
    }
    tracks_.push_back(std::move(track));
  }
  return report();
}

std::vector<TrackedPerson> MultiTracker::predict_only(int frame_index) {
  advance_to(frame_index);
  for (auto& t : tracks_) t->detection = -1;
  return report();
}

TrackedPerson MultiTracker::view(const Track& track) {
  TrackedPerson p;
  p.id = track.id;
  p.box = track.filter.box();
  p.state = track.state;
  p.hits = track.hits;
  p.frames_since_match = track.frames_since_match;
  p.detection = track.detection;
  return p;
}

std::vector<TrackedPerson> MultiTracker::report() const {
  std::vector<TrackedPerson> out;
  for (const auto& t : tracks_) {
    if (t->state == TrackState::kConfirmed ||
        (t->state == TrackState::kLost && t->frames_since_match <= options_.coast_frames))
      out.push_back(view(*t));
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return out;
}

std::vector<TrackedPerson> MultiTracker::all_tracks() const {
  std::vector<TrackedPerson> out;
  for (const auto& t : tracks_) out.push_back(view(*t));
  return out;
}

}  // namespace bodyrec
