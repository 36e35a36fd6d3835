#include "bodyrec/reid/online_reid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// Measurements that say what a body's stature is now (the last half second).
constexpr int kRecentStatures = 15;

}  // namespace

const char* reid_outcome_name(ReidOutcome outcome) {
  switch (outcome) {
    case ReidOutcome::kWaiting: return "waiting";
    case ReidOutcome::kRecognised: return "recognised";
    case ReidOutcome::kEnrolled: return "enrolled";
    case ReidOutcome::kStatureWait: return "stature_wait";
    case ReidOutcome::kVerified: return "verified";
    case ReidOutcome::kStrike: return "strike";
    case ReidOutcome::kReleased: return "released";
    case ReidOutcome::kUserErased: return "user_erased";
  }
  return "?";
}

void OnlineReidOptions::check() const {
  const auto fail = [](const char* field, const char* problem) { throw OptionError("OnlineReidOptions", field, problem); };
  if (decide_after < 1) fail("decide_after", "must be at least 1");
  if (max_wait_frames < 1) fail("max_wait_frames", "must be at least 1 frame");
  if (stature_wait_frames < 0) fail("stature_wait_frames", "must not be negative");
  if (max_scans < decide_after) fail("max_scans", "must be at least decide_after");
  if (sure_after < 1) fail("sure_after", "must be at least 1");
  if (!(min_quality >= 0 && min_quality <= 1)) fail("min_quality", "must be within 0..1");
  if (!(min_view_confidence >= 0 && min_view_confidence <= 1)) fail("min_view_confidence", "must be within 0..1");
  if (!(update_gain >= 1)) fail("update_gain", "must be at least 1");
  if (update_every < 1) fail("update_every", "must be at least 1");
  if (verify_every < 1) fail("verify_every", "must be at least 1");
  if (strikes < 1) fail("strikes", "must be at least 1");
  if (!(verify_quality >= 0 && verify_quality <= 1)) fail("verify_quality", "must be within 0..1");
  if (!(left_after_s >= 0)) fail("left_after_s", "must not be negative");
  if (std::isinf(threshold)) fail("threshold", "must be finite");
  if (!(margin >= 0)) fail("margin", "must not be negative");
  if (!(new_gap >= 0)) fail("new_gap", "must not be negative");
  if (!(stature_tolerance_m >= 0)) fail("stature_tolerance_m", "must not be negative");
  if (!(stature_weight >= 0)) fail("stature_weight", "must not be negative");
  if (!(stature_cap >= 0)) fail("stature_cap", "must not be negative");
}

OnlineReid::OnlineReid(ReidStore& store, const AppearanceMatcher& matcher, OnlineReidOptions options)
    : store_(store), matcher_(matcher), options_(std::move(options)) {
  options_.check();
  descriptor_ = matcher_.name() + "/" + matcher_.version();
  threshold_ = std::isnan(options_.threshold) ? matcher_.threshold() : options_.threshold;
  index_ = std::make_unique<GalleryIndex>(
      store_, matcher_, [this](const GalleryEntry& e) { return comparable(e); }, appearance_of);
}

void OnlineReid::changed(std::optional<UserId> user) {
  ++gallery_version_;
  if (user) index_->update(*user);
  else index_->reload();
}

bool OnlineReid::comparable(const GalleryEntry& e) const {
  return e.descriptor == descriptor_ && e.descriptor_version == kReidDescriptorVersion;
}

bool OnlineReid::usable(const ViewEstimate& view) const {
  return view.view && view.confidence >= options_.min_view_confidence;
}

bool OnlineReid::usable(const ReidBody& body) const {
  return usable(body.view) && body.scan && body.scan->quality >= options_.min_quality;
}

// Whether a scan of this quality would be stored for the user's view: the view is missing, was made by
// another matcher, or is clearly worse.
bool OnlineReid::improves(UserId user, View view, double quality) const {
  const GalleryEntry* stored = store_.find(user, view);
  return !stored || !comparable(*stored) || quality > options_.update_gain * stored->quality;
}

std::map<View, const OnlineReid::Probe*> OnlineReid::best_per_view(const std::vector<Probe>& probes,
                                                                   const std::vector<bool>& use) {
  std::map<View, const Probe*> best;
  for (size_t i = 0; i < probes.size(); ++i) {
    const Probe& p = probes[i];
    if (use[i] && (!best.count(p.view) || p.quality > best[p.view]->quality)) best[p.view] = &p;
  }
  return best;
}

std::optional<OnlineReid::Probe> OnlineReid::describe(const ReidBody& body) const {
  if (!usable(body)) return std::nullopt;
  Probe p;
  p.view = *body.view.view;
  p.quality = body.scan->quality;
  p.scan = *body.scan;
  p.descriptor = matcher_.describe(PersonImage{body.scan->image, body.scan->mask, body.scan->row_height_m});
  return p;
}

// Per user, the best similarity over the scans of the probe's view and its complementary views; users
// that have none of those are scored over all their views (a person seen from the front, now from the
// side, must still be found).
std::vector<OnlineReid::Score> OnlineReid::score_users(const Probe& probe, std::optional<UserId> only) const {
  std::vector<View> near = complementary_views(probe.view);
  near.push_back(probe.view);
  struct Best {
    std::optional<Score> near, any;
    std::optional<double> side;  // over the probe's own and complementary views only
  };
  // By the index's user slot (`only`: slot 0).
  std::vector<Best> best(only ? 1 : index_->slot_count());
  std::vector<double> sims;
  for (View v : kAllViews) {
    const bool same_side = std::find(near.begin(), near.end(), v) != near.end();
    const bool is_near = options_.all_views || same_side;
    const auto consider = [&](Best& b, UserId user, double s) {
      if (is_near && (!b.near || s > b.near->similarity)) b.near = Score{user, s, 0, v, true, std::nullopt};
      if (!b.any || s > b.any->similarity) b.any = Score{user, s, 0, v, false, std::nullopt};
      if (same_side && (!b.side || s > *b.side)) b.side = s;
    };
    if (only) {
      const GalleryEntry* e = store_.find(*only, v);
      if (e && comparable(*e)) consider(best[0], *only, matcher_.similarity(probe.descriptor, appearance_of(*e)));
      continue;
    }
    index_->search(v, probe.descriptor, sims);
    const std::vector<uint32_t>& slots = index_->slots(v);
    for (size_t i = 0; i < sims.size(); ++i) consider(best[slots[i]], index_->user(slots[i]), sims[i]);
  }
  std::vector<Score> out;
  for (const Best& b : best) {
    if (!b.any) continue;
    out.push_back(b.near ? *b.near : *b.any);
    out.back().same_side = b.side;
  }
  std::sort(out.begin(), out.end(), [](const Score& a, const Score& b) { return a.similarity > b.similarity; });
  return out;
}

const std::vector<OnlineReid::Score>& OnlineReid::scores(Probe& probe) {
  if (probe.scored_at != gallery_version_) {
    probe.scores = score_users(probe);
    probe.scored_at = gallery_version_;
  }
  return probe.scores;
}

const std::map<UserId, double>& OnlineReid::user_statures() {
  if (statures_at_ == gallery_version_) return user_statures_;
  // Per user, the stature of the scan with the most measurements behind it (the longest look).
  std::map<UserId, std::pair<double, float>> all;
  for (View v : kAllViews)
    for (const GalleryEntry& e : store_.scans(v))
      if (comparable(e))
        if (const auto s = stature_of(e)) {
          const float n = stature_count_of(e);
          const auto it = all.find(e.user);
          if (it == all.end() || n > it->second.second) all[e.user] = {*s, n};
        }
  user_statures_.clear();
  for (const auto& [user, value] : all) user_statures_[user] = value.first;
  statures_at_ = gallery_version_;
  return user_statures_;
}

std::vector<OnlineReid::Score> OnlineReid::with_stature(std::vector<Score> scores, std::optional<double> stature) {
  if (!stature || options_.stature_weight <= 0) return scores;
  const std::map<UserId, double>& users = user_statures();
  const double scale = std::abs(threshold_);
  for (Score& s : scores) {
    const auto it = users.find(s.user);
    if (it == users.end()) continue;
    const double beyond_cm = 100 * std::max(0.0, std::abs(*stature - it->second) - options_.stature_tolerance_m);
    s.stature = -std::min(options_.stature_cap, options_.stature_weight * beyond_cm) * scale;
    s.similarity += s.stature;
  }
  std::stable_sort(scores.begin(), scores.end(), [](const Score& a, const Score& b) { return a.similarity > b.similarity; });
  return scores;
}

// Users held by another track seen in this frame: two bodies in one frame are two people.
std::vector<UserId> OnlineReid::users_held_except(uint64_t key) const {
  std::vector<UserId> held;
  for (const auto& [k, t] : tracks_)
    if (k != key && t.user && t.last_seen >= now_) held.push_back(*t.user);
  return held;
}

GalleryScan OnlineReid::gallery_scan(const Probe& probe, const Track& track) const {
  GalleryScan g;
  g.view = probe.view;
  g.image = probe.scan.image;
  g.mask = probe.scan.mask;
  g.features = reid_features(probe.descriptor, track.stature.estimate(), track.stature.count());
  g.descriptor = descriptor_;
  g.descriptor_version = kReidDescriptorVersion;
  g.quality = probe.quality;
  return g;
}

bool OnlineReid::report(const ReidEvent& event, ReidStep& out) {
  if (!store_.log(event, now_)) return false;
  out.events.push_back(event);
  return true;
}

ReidTrace::Scan OnlineReid::trace_scan(const Probe& probe, const std::vector<Score>& scores) {
  ReidTrace::Scan t;
  t.view = probe.view;
  t.quality = probe.quality;
  for (size_t i = 0; i < scores.size() && i < 3; ++i)
    t.best.push_back({scores[i].user, scores[i].similarity, scores[i].stature, scores[i].view});
  return t;
}

bool OnlineReid::take_in_changes(ReidStep& out) {
  if (!store_.refresh()) return false;
  changed(std::nullopt);
  // Users erased by another process: their bodies are decided afresh.
  for (auto& [key, track] : tracks_)
    if (track.user && !store_.has_user(*track.user)) drop_user(key, track, out);
  return true;
}

void OnlineReid::drop_user(uint64_t key, Track& track, ReidStep& out) {
  if (options_.trace) out.trace.push_back({key, ReidOutcome::kUserErased, track.user, track.stature.estimate(), {}});
  track.user.reset();
  track.probes.clear();
  track.beside.clear();
  track.strikes = 0;
  track.frames = 0;
}

void OnlineReid::enrol(uint64_t key, Track& track, ReidStep& out) {
  // The best probe per view; the best of all is the enrolment scan.
  const std::map<View, const Probe*> best = best_per_view(track.probes, std::vector<bool>(track.probes.size(), true));
  const Probe* first = nullptr;
  for (const auto& [v, p] : best)
    if (!first || p->quality > first->quality) first = p;
  std::vector<GalleryScan> scans{gallery_scan(*first, track)};
  for (const auto& [v, p] : best)
    if (p != first) scans.push_back(gallery_scan(*p, track));
  const UserId user = store_.enrol(scans, key, now_);
  changed(user);
  out.events.push_back({ReidEventKind::kEnrolled, user, key, first->view, std::nullopt});
  track.user = user;
  track.last_verify = frame_;
  for (const auto& [v, p] : best)
    if (p != first) report({ReidEventKind::kViewAdded, user, key, v, std::nullopt}, out);
}

void OnlineReid::decide(uint64_t key, Track& track, ReidStep& out, bool locked) {
  // Users seen in another body while this one was in view (now or earlier) are someone else.
  std::vector<UserId> held = users_held_except(key);
  held.insert(held.end(), track.beside.begin(), track.beside.end());
  // Each scan votes: for the best user when it passes the threshold and stands out from the next one by
  // the margin; for "new" when even the best user is below the threshold by new_gap; not at all when
  // two users are too close to call or the best is in between.
  const double margin = options_.margin * std::abs(threshold_);
  const double new_gap = options_.new_gap * std::abs(threshold_);
  std::map<UserId, int> votes;
  std::map<UserId, double> sums, weakest;  // per user: sum and least of the voting similarities
  std::map<UserId, bool> stature_agrees;   // the track's stature was measured and matches the user's
  std::map<UserId, View> views;
  std::vector<int64_t> voted_for(track.probes.size(), -1);
  int for_new = 0;
  const std::optional<double> stature = track.stature.estimate();
  ReidTrace trace{key, ReidOutcome::kWaiting, std::nullopt, stature, {}};
  for (size_t i = 0; i < track.probes.size(); ++i) {
    std::vector<Score> s;
    for (const Score& x : with_stature(scores(track.probes[i]), stature))
      if (std::find(held.begin(), held.end(), x.user) == held.end()) s.push_back(x);
    if (options_.trace) trace.scans.push_back(trace_scan(track.probes[i], s));
    // "New": nobody passes the threshold in a comparison of the same side of the body (same or
    // complementary view: reliable), or even the best is far below it (across views).
    if (s.empty() || s.front().similarity < threshold_ - new_gap || (s.front().near && s.front().similarity <= threshold_)) {
      ++for_new;
      if (options_.trace) trace.scans.back().votes_new = true;
      continue;
    }
    if (s.front().similarity <= threshold_) continue;  // between "same" and "someone else": no vote
    if (s.size() > 1 && s[0].similarity - s[1].similarity < margin) continue;
    const UserId u = s.front().user;
    ++votes[u];
    sums[u] += s.front().similarity;
    weakest[u] = votes[u] == 1 ? s.front().similarity : std::min(weakest[u], s.front().similarity);
    stature_agrees[u] = stature && user_statures().count(u) && s.front().stature == 0;
    views[u] = track.probes[i].view;
    voted_for[i] = u;
    if (options_.trace) trace.scans.back().vote = u;
  }
  const auto done = [&](ReidOutcome outcome, std::optional<UserId> user) {
    if (!options_.trace) return;
    trace.outcome = outcome;
    trace.user = user;
    out.trace.push_back(std::move(trace));
  };
  const int n = static_cast<int>(track.probes.size());
  UserId winner = 0;
  int most = 0;
  for (const auto& [u, k] : votes)
    if (k > most) winner = u, most = k;
  const bool forced = track.frames >= options_.max_wait_frames;
  // Before decide_after scans only a sure recognition decides: every scan for the same user, each
  // clearly (new_gap above the threshold), and the stature measured and matching.
  const bool sure = most == n && n >= options_.sure_after && weakest[winner] >= threshold_ + new_gap &&
                    stature_agrees[winner];
  if (n < options_.decide_after && !forced && !sure) return done(ReidOutcome::kWaiting, std::nullopt);
  // A body whose stature is not measured yet (head not in view) is not recognised as a user whose
  // stature is known before stature_wait_frames or max_wait: two people who dress alike differ in
  // stature more often than not.
  const bool stature_pending = options_.stature_weight > 0 && !stature && user_statures().count(winner) && !forced &&
                               track.frames < options_.stature_wait_frames;
  if (!stature_pending && (sure || 2 * most > n || (forced && most > 0 && most >= for_new))) {
    if (!report({ReidEventKind::kRecognised, winner, key, views[winner], sums[winner] / most}, out)) {
      // The winner was erased a moment ago: its scans go when the store is refreshed; decide again then.
      drop_user(key, track, out);
      return;
    }
    done(ReidOutcome::kRecognised, winner);
    track.user = winner;
    track.last_verify = frame_;
    // A track that held this user but is not in this frame was the same body under an older key.
    for (auto& [k, t] : tracks_)
      if (k != key && t.user == winner) t.last_seen = -1e300;
    // The scans that voted for this user add the views it lacks (or improve them).
    std::vector<bool> voted(track.probes.size());
    for (size_t i = 0; i < voted.size(); ++i) voted[i] = voted_for[i] == winner;
    for (const auto& [v, p] : best_per_view(track.probes, voted)) {
      if (!improves(winner, v, p->quality)) continue;
      const std::optional<PutResult> put = store_.put_scan(winner, gallery_scan(*p, track), now_);
      if (!put) return drop_user(key, track, out);
      changed(winner);
      if (*put == PutResult::kInserted) report({ReidEventKind::kViewAdded, winner, key, v, std::nullopt}, out);
    }
  } else if (stature_pending && 2 * most > n) {
    return done(ReidOutcome::kStatureWait, winner);  // recognised by appearance; wait for the stature
  } else if (2 * for_new > n || (forced && for_new > 0 && for_new >= most) ||
             track.frames >= 3 * options_.max_wait_frames) {
    // (Scans that all fall between "same" and "someone else" wait three times longer before enrolling:
    // that is more often a known person half hidden or turned than a new one.)
    if (locked) {
      enrol(key, track, out);
    } else {
      // Decided on the gallery as of this step's refresh: with other writers kept out, take in what they
      // wrote since and decide again when anything changed (another sensor may have enrolled this person).
      bool again = false;
      store_.exclusive([&] { (again = take_in_changes(out)) ? decide(key, track, out, true) : enrol(key, track, out); });
      if (again) return;
    }
    done(ReidOutcome::kEnrolled, track.user);
  } else {
    return done(ReidOutcome::kWaiting, std::nullopt);  // too close to call, or contradicting: collect more
  }
  track.probes.clear();
}

void OnlineReid::update(uint64_t key, Track& track, const ReidBody& body, ReidStep& out) {
  if (!usable(body)) return;
  const UserId user = *track.user;
  const View view = *body.view.view;
  const bool better = improves(user, view, body.scan->quality);
  const bool verify = frame_ - track.last_verify >= options_.verify_every;
  if (!verify && !(better && frame_ - track.last_describe >= options_.update_every)) return;
  track.last_describe = frame_;
  std::optional<Probe> probe = describe(body);
  if (!probe) return;
  ++out.described;
  std::optional<Score> mine;
  double best_other = -std::numeric_limits<double>::infinity();
  // The track's own user by appearance alone (its stored stature may come from this very track's
  // earlier, rougher estimate); everyone else with the stature term, and only when the scan may be
  // stored (below): a check alone scores the track's user only.
  const std::optional<UserId> only = better ? std::nullopt : std::optional<UserId>(user);
  const std::vector<Score> scored = with_stature(score_users(*probe, only), track.stature.estimate());
  for (const Score& s : scored)
    if (s.user == user) mine = s, mine->similarity -= s.stature, mine->stature = 0;
    else best_other = std::max(best_other, s.similarity);
  const double clear_miss = threshold_ - options_.new_gap * std::abs(threshold_);
  if (verify) {
    track.last_verify = frame_;
    // Only a comparison with the same or a complementary view can say "not this user": the other
    // side of a person may look different.
    const bool side = mine && mine->same_side;
    // A body that still has its user's stature is more likely the same person turned or seen poorly
    // than another one: it takes twice as many failed checks in a row (unknown statures leave it to
    // the appearance).
    const auto now = track.stature.estimate(kRecentStatures);
    const auto them = user_statures().find(user);
    const bool same_stature = options_.stature_weight > 0 && now && them != user_statures().end() &&
                              std::abs(*now - them->second) <= options_.stature_tolerance_m;
    if (side && probe->quality >= options_.verify_quality)
      track.strikes = *mine->same_side < clear_miss ? track.strikes + 1 : 0;
    const bool release = track.strikes >= options_.strikes * (same_stature ? 2 : 1);
    if (options_.trace)
      out.trace.push_back({key, release ? ReidOutcome::kReleased : track.strikes ? ReidOutcome::kStrike : ReidOutcome::kVerified,
                           user, now, {trace_scan(*probe, scored)}});
    if (release) {
      // Not this user any more: release it and decide the body afresh from this scan on.
      report({ReidEventKind::kLeft, user, key, std::nullopt, std::nullopt}, out);
      track.user.reset();
      track.beside.clear();  // (the failed user stays a candidate: a check can fail on a turned body)
      track.strikes = 0;
      track.frames = 1;
      track.probes.assign(1, std::move(*probe));
      return;
    }
  }
  // A known view must still match this user (not someone who stepped in front); a new view must not
  // look like anybody else.
  if (!better || track.strikes > 0 || !mine) return;
  const bool ok = mine->near ? mine->similarity > threshold_ : best_other <= threshold_ && mine->similarity > clear_miss;
  if (!ok) return;
  const std::optional<PutResult> put = store_.put_scan(user, gallery_scan(*probe, track), now_);
  if (!put) return drop_user(key, track, out);
  changed(user);
  if (*put == PutResult::kInserted) report({ReidEventKind::kViewAdded, user, key, view, std::nullopt}, out);
}

void OnlineReid::leave(uint64_t key, Track& track, ReidStep& out) {
  // A pending track with enough evidence (decide_after scans, or seen for max_wait frames) is decided
  // as it leaves, so a short visit still enrols; a glimpse (a segment that flickered into view for a
  // few frames) leaves nothing behind.
  const bool visit = static_cast<int>(track.probes.size()) >= options_.decide_after || track.frames >= options_.max_wait_frames;
  if (!track.user && !track.probes.empty() && visit) {
    track.frames = std::max(track.frames, options_.max_wait_frames);
    decide(key, track, out);
  }
  if (track.user) report({ReidEventKind::kLeft, *track.user, key, std::nullopt, std::nullopt}, out);
}

bool OnlineReid::wants_scan(uint64_t track, const ViewEstimate& view) const {
  if (!usable(view)) return false;
  const auto it = tracks_.find(track);
  if (it == tracks_.end() || !it->second.user) return true;
  if (frame_ + 1 - it->second.last_verify >= options_.verify_every) return true;
  if (frame_ + 1 - it->second.last_describe < options_.update_every) return false;
  return improves(*it->second.user, *view.view, 1.0);  // could the best possible scan (quality 1) improve it?
}

ReidStep OnlineReid::step(double time_s, const std::vector<ReidBody>& bodies) {
  ++frame_;
  now_ = time_s;
  ReidStep out;
  take_in_changes(out);
  for (const ReidBody& b : bodies) {
    Track& t = tracks_[b.track];
    t.last_seen = time_s;
    ++t.frames;
    if (b.stature_m) t.stature.add(*b.stature_m);
  }
  for (const ReidBody& b : bodies) {
    Track& t = tracks_[b.track];
    if (!t.user) {
      for (UserId u : users_held_except(b.track)) t.beside.insert(u);
      if (std::optional<Probe> p = describe(b)) {
        ++out.described;
        t.probes.push_back(std::move(*p));
        // Keep the evidence bounded: drop the poorest scan.
        if (t.probes.size() > static_cast<size_t>(options_.max_scans))
          t.probes.erase(std::min_element(t.probes.begin(), t.probes.end(),
                                          [](const Probe& a, const Probe& c) { return a.quality < c.quality; }));
      }
      const int n = static_cast<int>(t.probes.size());
      if (n >= std::min(options_.decide_after, options_.sure_after) || (n > 0 && t.frames >= options_.max_wait_frames))
        decide(b.track, t, out);
    } else {
      update(b.track, t, b, out);
    }
    out.identities.push_back({b.track, t.user, b.view.view, b.box});
  }
  for (auto it = tracks_.begin(); it != tracks_.end();) {
    if (it->second.last_seen < time_s - options_.left_after_s) {
      leave(it->first, it->second, out);
      it = tracks_.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

std::vector<ReidEvent> OnlineReid::finish() {
  ReidStep out;
  for (auto& [key, track] : tracks_) leave(key, track, out);
  tracks_.clear();
  return out.events;
}

}  // namespace bodyrec
