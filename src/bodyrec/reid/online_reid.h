// Online re-identification (thesis Ch6, 3D Partial Scans Models), several bodies at once, with a
// persistent gallery: decides per tracked body whether it is a known user or a new one, keeps each
// user's best scan per view, and reports what happened as events.
//
// Per track (a sensor tracking id, a body-index slot or a floor tracker's key):
//  - pending: every usable scan (a view with enough confidence, quality >= min_quality) is described and
//    scored against the gallery: per user, the best appearance similarity over the user's scans of the
//    same view and its complementary views (reid/view.h), falling back to all the user's views when it
//    has none of those (all_views, --match-views all, the default: every view at once), plus a stature
//    term: a user whose stature differs from the track's (body_measures.h) by more than a tolerance
//    loses score per centimetre. A scan votes for its best user when that passes the threshold and
//    beats the next user by a margin, for "new" when the best user fails the threshold on the same side of the body or is well below it
//    (new_gap) across views, and abstains otherwise. Once `decide_after` scans are in, the track is
//    recognised as the user with a majority of the votes, or enrolled as a new user (best scan per view)
//    when most scans say "new"; otherwise it collects more, and after max_wait_frames it is decided by
//    the larger side (when no scan voted at all, it waits up to three times as long, then enrols). Sooner,
//    after `sure_after` scans, only a sure recognition: every scan clearly (new_gap above the threshold)
//    for one user whose stature matches. A body whose stature is not measured yet is not recognised as a
//    user with a known stature before stature_wait_frames (or max_wait). Users held by another track in
//    a frame this one was in are never candidates: two bodies in one frame are two people (no merges).
//  - assigned: a scan of a view the user lacks, or clearly better than the stored one, is checked against
//    the user and stored (`view_added` or a silent replacement): it must match the user when the user has
//    that view or a complementary one, and match nobody else when the view is new. Every few frames the
//    body is checked against its user's scans of the same side of the body (its view or a complementary
//    one); a track that keeps failing (it jumped to someone else) is released (`left` for that user) and
//    decided afresh: after `strikes` failed checks in a row, twice as many while the body's recent
//    stature still matches the user's.
//  - a track unseen for left_after_s has left (`left`); a pending track that leaves with decide_after
//    scans, or after max_wait frames in view, is decided first with what it has (as after max_wait); a
//    glimpse (fewer scans and frames: a segment that flickered into view) leaves nothing behind.
// A user who comes back gets a new track and is recognised again from the gallery.
// A user erased meanwhile (another process's `gallery forget`, taken in by the store's refresh() at the next
// step) is dropped: a body that was that user is decided afresh, and nothing of the user is written back.
// Users and views other processes add are taken in the same way, at every step. An enrolment is final only
// inside the store's exclusive() (one write transaction that keeps other writers out): there the track
// takes in what others wrote since the step began and, when anything changed, is decided again, so two
// sensors meeting the same new person at the same moment make one user and the later one recognises it.
//
// The decisions know nothing of storage: they read and write a ReidStore (reid_store.h), a persistent
// gallery (GalleryReidStore) or memory (MemoryReidStore).
//
//   GalleryReidStore store(gallery, *matcher, {"camera 0"});
//   OnlineReid reid(store, *matcher);
//   for (each frame) {
//     std::vector<ReidBody> bodies = ...;  // track, view, scan (optional), box
//     const ReidStep out = reid.step(time_s, bodies);   // out.identities[i].user, out.events
//   }
//   reid.finish();  // `left` for everyone still in view
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/reid/appearance_matcher.h"
#include "bodyrec/reid/body_measures.h"
#include "bodyrec/reid/gallery_index.h"
#include "bodyrec/reid/partial_scan.h"
#include "bodyrec/reid/reid_event.h"
#include "bodyrec/reid/reid_features.h"
#include "bodyrec/reid/reid_store.h"

namespace bodyrec {

struct OnlineReidOptions {
  int decide_after = 4;         // scans a pending track collects before deciding
  // ... unless its first sure_after scans all vote clearly (new_gap above the threshold) for the same
  // user whose stature matches the body's: then it is recognised at once. >= decide_after: never early.
  int sure_after = 2;
  int max_wait_frames = 30;     // then decide with whatever scans there are (at least one)
  // A body whose stature is not measured yet is recognised as a user of known stature only after this
  // many frames (max_wait_frames decides when sooner): the stature keeps apart people who dress alike.
  // 0 = no wait (the stature still counts once measured).
  int stature_wait_frames = 30;
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
  // Stature (body_measures.h), fused with the appearance score: a user whose stored stature differs
  // from the track's by more than stature_tolerance_m loses stature_weight x |threshold| per centimetre
  // beyond it, at most stature_cap x |threshold|. Unknown statures (no measurement yet, or scans
  // described again from an older gallery) cost nothing. stature_weight 0 = appearance only.
  double stature_tolerance_m = 0.04;
  double stature_weight = 0.1;
  double stature_cap = 1.6;
  bool trace = false;           // fill ReidStep::trace with every decision's evidence
  void check() const;           // UsageError naming the field
};

// One body in one frame as the pipeline gives it.
struct ReidBody {
  uint64_t track = 0;             // stable while the body stays in view
  ViewEstimate view;
  std::optional<PartialScan> scan;  // none when the body gave no usable scan this frame
  std::optional<double> stature_m;  // this frame's stature measurement (body_measures.h), if any
  cv::Rect box;                   // colour pixels, for the output only
};

struct ReidIdentity {
  uint64_t track = 0;
  std::optional<UserId> user;   // none while the track is still collecting evidence
  std::optional<View> view;
  cv::Rect box;
};

// Why a decision came out as it did (OnlineReidOptions::trace): the evidence of one decision or check.
enum class ReidOutcome {
  kWaiting,        // pending: not enough evidence yet
  kRecognised,
  kEnrolled,
  kStatureWait,    // recognised by appearance; waiting for the body's stature to confirm it
  kVerified,       // an assigned track's check passed (or could not fail)
  kStrike,         // an assigned track's check failed
  kReleased,       // too many failed checks: the user is released and the body decided afresh
  kUserErased,     // the track's user was erased from the gallery: decided afresh
};
const char* reid_outcome_name(ReidOutcome outcome);

struct ReidCandidate {
  UserId user = 0;
  double similarity = 0;  // appearance + stature term
  double stature = 0;     // the stature term in it (<= 0)
  View view = View::F;    // the user's view it was compared with
};

struct ReidTrace {
  uint64_t track = 0;
  ReidOutcome outcome = ReidOutcome::kWaiting;
  std::optional<UserId> user;        // recognised / enrolled / checked / released user
  std::optional<double> stature_m;   // the track's stature estimate
  struct Scan {
    View view = View::F;
    double quality = 0;
    std::vector<ReidCandidate> best;  // the three best candidates (users held by other bodies left out)
    std::optional<UserId> vote;       // the user it voted for
    bool votes_new = false;           // it voted "new person"
  };
  std::vector<Scan> scans;           // a decision: every scan; a check: the one checked
};

struct ReidStep {
  std::vector<ReidIdentity> identities;  // one per input body, same order
  std::vector<ReidEvent> events;
  std::vector<ReidTrace> trace;          // with OnlineReidOptions::trace
  int described = 0;                     // scans described this frame (what costs)
};

class OnlineReid {
 public:
  // `store` and `matcher` must outlive this object. Stored scans of another matcher (name and version)
  // are ignored for matching and replaced when this matcher stores that view.
  OnlineReid(ReidStore& store, const AppearanceMatcher& matcher, OnlineReidOptions options = {});

  // One frame, bodies of that frame; time_s increasing. Writes to the store (enrolments, views, events)
  // as decisions are made.
  ReidStep step(double time_s, const std::vector<ReidBody>& bodies);
  // Decides pending tracks that have enough scans (as leave does) and ends every track (`left`), e.g. at
  // the end of a recording.
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
    double similarity = 0;  // appearance + stature term (the appearance alone in a probe's cache)
    double stature = 0;     // the stature term in `similarity` (<= 0)
    View view = View::F;
    bool near = false;  // from a view compared under --match-views (all views: always)
    // The best appearance similarity over the user's scans of the probe's own and complementary views
    // (the same side of the body); none when the user has no such view.
    std::optional<double> same_side;
  };
  struct Probe {
    View view;
    std::vector<float> descriptor;
    double quality = 0;
    PartialScan scan;
    std::vector<Score> scores;   // appearance against the whole gallery, best first
    int64_t scored_at = -1;      // gallery_version_ the scores belong to
  };
  struct Track {
    std::optional<UserId> user;
    std::vector<Probe> probes;  // pending only: the scans collected so far
    std::set<UserId> beside;    // pending only: users held by other bodies in frames this one was in
    StatureTrack stature;
    int frames = 0, last_describe = -1000000, last_verify = 0, strikes = 0;
    double last_seen = 0;
  };
  // Every user's (or only `only`'s) best appearance similarity to the probe, best first (no exclusions).
  std::vector<Score> score_users(const Probe& probe, std::optional<UserId> only = std::nullopt) const;
  // The same, cached in the probe until the gallery changes.
  const std::vector<Score>& scores(Probe& probe);
  // Appearance scores with the stature term of a track whose stature is `stature`, best first.
  std::vector<Score> with_stature(std::vector<Score> scores, std::optional<double> stature);
  // Each user's stature: that of their scan with the most measurements behind it (cached per gallery
  // version).
  const std::map<UserId, double>& user_statures();
  bool usable(const ViewEstimate& view) const;
  bool usable(const ReidBody& body) const;  // a view confident enough and a scan good enough
  bool improves(UserId user, View view, double quality) const;
  // The best probe per view among those with use[i].
  static std::map<View, const Probe*> best_per_view(const std::vector<Probe>& probes, const std::vector<bool>& use);
  std::optional<Probe> describe(const ReidBody& body) const;
  // `locked`: inside the store's exclusive(), with what others wrote taken in (an enrolment is then final).
  void decide(uint64_t key, Track& track, ReidStep& out, bool locked = false);
  void enrol(uint64_t key, Track& track, ReidStep& out);
  void update(uint64_t key, Track& track, const ReidBody& body, ReidStep& out);
  std::vector<UserId> users_held_except(uint64_t key) const;
  void leave(uint64_t key, Track& track, ReidStep& out);
  // Takes in what other writers changed (ReidStore::refresh): every cache is stale, and bodies whose user
  // was erased are decided afresh. True when anything changed.
  bool take_in_changes(ReidStep& out);
  // The track's user was erased: the body is decided afresh (from its next scans).
  void drop_user(uint64_t key, Track& track, ReidStep& out);
  bool comparable(const GalleryEntry& entry) const;  // made by this matcher in the current layout
  // The store changed: every cache is stale; the index takes `user`'s scans again (none: all of them).
  void changed(std::optional<UserId> user);
  GalleryScan gallery_scan(const Probe& probe, const Track& track) const;
  // Reports the event and logs it in the store; false (nothing reported) when the user was erased.
  bool report(const ReidEvent& event, ReidStep& out);
  static ReidTrace::Scan trace_scan(const Probe& probe, const std::vector<Score>& scores);

  ReidStore& store_;
  const AppearanceMatcher& matcher_;
  OnlineReidOptions options_;
  std::string descriptor_;  // matcher name/version as stored in the gallery
  double threshold_ = 0;
  std::map<uint64_t, Track> tracks_;
  int frame_ = 0;
  double now_ = 0;
  std::unique_ptr<GalleryIndex> index_;  // this matcher's scans, searched by score_users
  int64_t gallery_version_ = 0;  // bumped by every store write and by refresh() loading others' writes
  std::map<UserId, double> user_statures_;
  int64_t statures_at_ = -1;     // gallery_version_ of user_statures_
};

}  // namespace bodyrec
