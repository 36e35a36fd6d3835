#include "bodyrec/groups/leader_tracker.h"

#include <algorithm>

#include <dlib/image_processing.h>
#include <dlib/opencv.h>

#include "bodyrec/core/error.h"

namespace bodyrec {

void LeaderTrackerOptions::check() const {
  const auto fail = [](const char* field, const char* problem) { throw OptionError("LeaderTrackerOptions", field, problem); };
  if (!(min_psr >= 0)) fail("min_psr", "must be >= 0");
  if (max_disagreement < 1) fail("max_disagreement", "must be >= 1");
  if (max_unsupported < 1) fail("max_unsupported", "must be >= 1");
  if (!(disagree_iou >= 0 && disagree_iou <= 1)) fail("disagree_iou", "must be in 0..1");
  if (!(reacquire_iou > 0 && reacquire_iou <= 1)) fail("reacquire_iou", "must be in (0, 1]");
  if (reacquire_frames < 0) fail("reacquire_frames", "must be >= 0");
  if (!(max_outside > 0 && max_outside <= 1)) fail("max_outside", "must be in (0, 1]");
}

std::string to_string(LeaderState state) {
  switch (state) {
    case LeaderState::kTracking: return "tracking";
    case LeaderState::kLost: return "lost";
    case LeaderState::kNone: break;
  }
  return "none";
}

struct LeaderTracker::Dsst {
  dlib::correlation_tracker tracker;
};

LeaderTracker::LeaderTracker(const LeaderTrackerOptions& options) : options_(options) { options_.check(); }
LeaderTracker::~LeaderTracker() = default;
LeaderTracker::LeaderTracker(LeaderTracker&&) noexcept = default;
LeaderTracker& LeaderTracker::operator=(LeaderTracker&&) noexcept = default;

namespace {

dlib::drectangle to_dlib(const Box& b) { return {b.x, b.y, b.x + b.width - 1, b.y + b.height - 1}; }
Box from_dlib(const dlib::drectangle& r) { return {r.left(), r.top(), r.width(), r.height()}; }

const TrackedPerson* find_track(const std::vector<TrackedPerson>& tracks, int id) {
  for (const auto& t : tracks)
    if (t.id == id) return &t;
  return nullptr;
}

}  // namespace

void LeaderTracker::start(const cv::Mat& grey, const Box& box) {
  dsst_ = std::make_unique<Dsst>();
  dsst_->tracker.start_track(dlib::cv_image<unsigned char>(grey), to_dlib(box));
  last_good_ = box;
  disagreement_ = 0;
  unsupported_ = 0;
  frames_lost_ = 0;
}

const TrackedPerson* LeaderTracker::successor(const std::vector<TrackedPerson>& tracks, const Box& where) const {
  const TrackedPerson* best = nullptr;
  double best_iou = options_.reacquire_iou;
  for (const auto& t : tracks)
    if (t.id > newest_id_seen_ && t.state == TrackState::kConfirmed && t.frames_since_match == 0 &&
        iou(t.box, where) >= best_iou) {
      best = &t;
      best_iou = iou(t.box, where);
    }
  return best;
}

void LeaderTracker::hand_over(const cv::Mat& grey, const TrackedPerson& to) {
  status_.handed_over_from = status_.track_id;
  status_.track_id = to.id;
  start(grey, to.box);
  status_.state = LeaderState::kTracking;
  status_.box = to.box;
  status_.reacquired = true;
}

LeaderStatus LeaderTracker::update(const cv::Mat& grey, const std::vector<TrackedPerson>& tracks,
                                   std::optional<int> leader_id) {
  if (grey.type() != CV_8UC1) throw ProcessingError("leader tracker needs an 8-bit grey image");
  status_.reacquired = false;
  status_.handed_over_from.reset();
  status_.lost_reason.clear();
  if (!leader_id) {
    dsst_.reset();
    status_ = LeaderStatus{};
    return status_;
  }
  const TrackedPerson* leader = find_track(tracks, *leader_id);
  const bool detected = leader && leader->frames_since_match == 0;
  if (leader)  // successors must be tracks born after the leader was last seen
    for (const auto& t : tracks) newest_id_seen_ = std::max(newest_id_seen_, t.id);

  if (*leader_id != status_.track_id) {  // a new leader from the role logic
    status_ = LeaderStatus{};
    status_.track_id = *leader_id;
    if (!leader) return status_;  // not visible: wait for it
    start(grey, leader->box);
    status_.state = LeaderState::kTracking;
    status_.box = leader->box;
    return status_;
  }

  if (status_.state == LeaderState::kTracking) {
    status_.psr = dsst_->tracker.update(dlib::cv_image<unsigned char>(grey));
    const Box box = from_dlib(dsst_->tracker.get_position());
    const Box inside = clip_box(box, grey.size());
    disagreement_ = detected && iou(box, leader->box) < options_.disagree_iou ? disagreement_ + 1 : 0;
    const bool supported = std::any_of(tracks.begin(), tracks.end(), [&](const TrackedPerson& t) {
      return t.frames_since_match == 0 && iou(t.box, box) >= options_.disagree_iou;
    });
    unsupported_ = supported ? 0 : unsupported_ + 1;
    if (status_.psr < options_.min_psr) status_.lost_reason = "weak peak";
    else if (disagreement_ >= options_.max_disagreement) status_.lost_reason = "disagrees";
    else if (unsupported_ >= options_.max_unsupported) status_.lost_reason = "unsupported";
    else if (box.area() <= 0 || inside.area() < (1 - options_.max_outside) * box.area())
      status_.lost_reason = "left image";
    if (status_.lost_reason.empty()) {
      // Confident: carry the leader through detector misses; a new track on the DSST box after the
      // leader's track ended is the leader under a new id.
      if (!leader)
        if (const TrackedPerson* next = successor(tracks, box)) {
          hand_over(grey, *next);
          return status_;
        }
      status_.box = detected ? leader->box : box;
      last_good_ = status_.box;
      return status_;
    }
    status_.state = LeaderState::kLost;
    status_.box = Box();
    frames_lost_ = 0;
    return status_;
  }

  // Lost: re-acquire from the leader's own track when it is detected again, or hand the role to the new
  // track that took its place near the last reliable leader box.
  ++frames_lost_;
  if (detected) {
    start(grey, leader->box);
    status_.state = LeaderState::kTracking;
    status_.box = leader->box;
    status_.reacquired = true;
  } else if (!leader && frames_lost_ <= options_.reacquire_frames) {
    if (const TrackedPerson* next = successor(tracks, last_good_)) hand_over(grey, *next);
  }
  return status_;
}

}  // namespace bodyrec
