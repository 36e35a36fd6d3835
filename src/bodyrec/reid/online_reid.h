// Online re-identification (thesis Ch6, 3D Partial Scans Models), several bodies at once, with a
// persistent gallery: decides per tracked body whether it is a known user or a new one, keeps each
// user's best scan per view, and reports what happened as events.
//
// Per track (a sensor tracking id, a body-index slot or a segment tracker's key):
//  - pending: every usable scan (a view with enough confidence, quality >= min_quality) is described and
//    scored against the gallery: per user, the best similarity over the user's scans of the same view and
//    its complementary views (reid/view.h), or over all the user's views when it has none of those. A scan
//    votes for its best user when that passes the threshold and beats the next user by a margin, for "new"
//    when the best user fails the threshold on the same side of the body (same or complementary view) or
//    is well below it (new_gap) across views, and abstains otherwise. Once `decide_after` scans are in, the track is recognised
//    as the user with a majority of the votes, or enrolled as a new user (best scan per view) when most
//    scans say "new"; otherwise it collects more, and after max_wait_frames it is decided by the larger
//    side (when no scan voted at all, it waits up to three times as long, then enrols). Users held by another track in the same frame are never candidates: two bodies in one frame
//    are two people (no merges).
//  - assigned: a scan of a view the user lacks, or clearly better than the stored one, is checked against
//    the user and stored (`view_added` or a silent replacement): it must match the user when the user has
//    that view or a complementary one, and match nobody else when the view is new. Every few frames the
//    body is checked against its user's scans of that view or a complementary one; a track that keeps
//    failing (it jumped to someone else) is released (`left` for that user) and decided afresh.
//  - a track unseen for left_after_s has left (`left`); a pending track that leaves with scans is decided
//    first, so a short visit still enrols.
// A user who comes back gets a new track and is recognised again from the gallery.
//
//   OnlineReid reid(gallery, *matcher);
//   for (each frame) {
//     std::vector<ReidBody> bodies = ...;  // track, view, scan (optional), box
//     const ReidStep out = reid.step(time_s, bodies);   // out.identities[i].user, out.events
//   }
//   reid.finish(last_time_s);  // `left` for everyone still in view
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/reid/appearance_matcher.h"
#include "bodyrec/reid/partial_scan.h"
#include "bodyrec/store/gallery.h"

namespace bodyrec {

struct OnlineReidOptions {
  int decide_after = 4;         // scans a pending track collects before deciding
  int max_wait_frames = 30;     // then decide with whatever scans there are (at least one)
  int max_scans = 12;           // a pending track keeps at most this many scans (the best ones)
  double min_quality = 0.35;    // scans below this PartialScan::quality are not used
  double min_view_confidence = 0.2;  // bodies whose view is less certain give no scan
  double update_gain = 1.15;    // an assigned track replaces a stored scan when quality > gain x stored
  int update_every = 5;         // an assigned track describes at most one scan per this many frames
  double left_after_s = 1.0;    // a track unseen this long has left (a sensor keeps ids through short occlusions)
  // An assigned track checks every this many frames that it still shows its user; after `strikes`
  // checks in a row that clearly fail (below threshold - new_gap), the user is released and the track
  // decided afresh (a sensor's or segmenter's track that jumped to another person).
  int verify_every = 10;
  int strikes = 2;
  double verify_quality = 0.6;  // only scans this good can strike (occluded bodies look like someone else)
  // Similarity above which a scan is called the user's; NaN = the matcher's threshold().
  double threshold = std::numeric_limits<double>::quiet_NaN();
  // A scan votes for its best user only when it beats the next user by this share of |threshold|.
  double margin = 0.3;
  // Across views (the user has no scan of this side of the body), a scan votes "new person" only when
  // its best user is below the threshold by this share of |threshold|; in between it does not vote.
  double new_gap = 0.6;
  // Views: "near" compares a scan with the user's scans of the same and complementary views (the
  // thesis), falling back to all views when the user has none of those; "all" with every view.
  bool all_views = true;
  std::string source;           // recording or camera name written with the gallery's events
  void check() const;           // UsageError naming the field
};

// One body in one frame as the pipeline gives it.
struct ReidBody {
  uint64_t track = 0;             // stable while the body stays in view
  ViewEstimate view;
  std::optional<PartialScan> scan;  // none when the body gave no usable scan this frame
  cv::Rect box;                   // colour pixels, for the output only
};

enum class ReidEventKind { kEnrolled, kRecognised, kViewAdded, kLeft };
const char* reid_event_name(ReidEventKind kind);  // "enrolled", "recognised", "view_added", "left"

struct ReidEvent {
  ReidEventKind kind = ReidEventKind::kRecognised;
  UserId user = 0;
  uint64_t track = 0;
  std::optional<View> view;     // the view matched / added / enrolled with
  std::optional<double> score;  // recognised: the winning mean similarity
};

struct ReidIdentity {
  uint64_t track = 0;
  std::optional<UserId> user;   // none while the track is still collecting evidence
  std::optional<View> view;
  cv::Rect box;
};

struct ReidStep {
  std::vector<ReidIdentity> identities;  // one per input body, same order
  std::vector<ReidEvent> events;
  int described = 0;                     // scans described this frame (what costs)
};

class OnlineReid {
 public:
  // `gallery` and `matcher` must outlive this object. Gallery scans of another descriptor (matcher name
  // and version) are ignored for matching and replaced when this matcher stores that view.
  OnlineReid(Gallery& gallery, const AppearanceMatcher& matcher, OnlineReidOptions options = {});

  // One frame, bodies of that frame; time_s increasing. Writes to the gallery (enrolments, views,
  // events) as decisions are made; each write is its own transaction (an enrolment with all its views one).
  ReidStep step(double time_s, const std::vector<ReidBody>& bodies);
  // Decides pending tracks that have scans and ends every track (`left`), e.g. at the end of a recording.
  std::vector<ReidEvent> finish();

  // Whether the next step() would use a scan of this body: pending tracks always, assigned tracks when
  // their view is missing or might be improved and the update interval has passed. The caller skips
  // extracting scans nobody wants (the scan costs more than the decision).
  bool wants_scan(uint64_t track, const ViewEstimate& view) const;

  double threshold() const { return threshold_; }
  // Live tracks (pending or assigned); bounded by the bodies in view.
  size_t live_tracks() const { return tracks_.size(); }

 private:
  struct Score {
    UserId user = 0;
    double similarity = 0;
    View view = View::F;
    bool near = false;  // from the probe's own or a complementary view (else the user has none of those)
  };
  struct Probe {
    View view;
    std::vector<float> descriptor;
    double quality = 0;
    PartialScan scan;
    std::vector<Score> scores;   // against the whole gallery, best first
    int64_t scored_at = -1;      // gallery_version_ the scores belong to
  };
  struct Track {
    std::optional<UserId> user;
    std::vector<Probe> probes;  // pending only: the scans collected so far
    int frames = 0, last_describe = -1000000, last_verify = 0, strikes = 0;
    double last_seen = 0;
  };
  // Every user's best similarity to the probe, best first (no exclusions).
  std::vector<Score> score_users(const Probe& probe) const;
  // The same, cached in the probe until the gallery changes.
  const std::vector<Score>& scores(Probe& probe);
  bool usable(const ViewEstimate& view) const;
  bool usable(const ReidBody& body) const;  // a view confident enough and a scan good enough
  bool improves(UserId user, View view, double quality) const;
  // The best probe per view among those with use[i].
  static std::map<View, const Probe*> best_per_view(const std::vector<Probe>& probes, const std::vector<bool>& use);
  std::optional<Probe> describe(const ReidBody& body) const;
  void decide(uint64_t key, Track& track, std::vector<ReidEvent>& events);
  void enrol(uint64_t key, Track& track, std::vector<ReidEvent>& events);
  void update(uint64_t key, Track& track, const ReidBody& body, std::vector<ReidEvent>& events, int& described);
  std::vector<UserId> users_held_except(uint64_t key) const;
  void leave(uint64_t key, Track& track, std::vector<ReidEvent>& events);
  GalleryScan gallery_scan(const Probe& probe) const;
  void log(const ReidEvent& event);

  Gallery& gallery_;
  const AppearanceMatcher& matcher_;
  OnlineReidOptions options_;
  std::string descriptor_;  // matcher name/version as stored in the gallery
  double threshold_ = 0;
  bool debug_ = false;  // BODYREC_REID_DEBUG set: every decision's scores on stderr
  std::map<uint64_t, Track> tracks_;
  int frame_ = 0;
  double now_ = 0;
  int64_t gallery_version_ = 0;  // bumped by every gallery write and by refresh() loading others' writes
};

}  // namespace bodyrec
