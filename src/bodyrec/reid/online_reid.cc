#include "bodyrec/reid/online_reid.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

std::vector<float> as_vector(const cv::Mat& m) {
  CV_Assert(m.type() == CV_32F && m.isContinuous());
  const float* p = m.ptr<float>();
  return std::vector<float>(p, p + m.total());
}

EventKind store_kind(ReidEventKind kind) {
  switch (kind) {
    case ReidEventKind::kEnrolled: return EventKind::kEnrolled;
    case ReidEventKind::kRecognised: return EventKind::kRecognised;
    case ReidEventKind::kViewAdded: return EventKind::kViewAdded;
    case ReidEventKind::kLeft: return EventKind::kLeft;
  }
  return EventKind::kRecognised;
}

}  // namespace

const char* reid_event_name(ReidEventKind kind) {
  switch (kind) {
    case ReidEventKind::kEnrolled: return "enrolled";
    case ReidEventKind::kRecognised: return "recognised";
    case ReidEventKind::kViewAdded: return "view_added";
    case ReidEventKind::kLeft: return "left";
  }
  return "?";
}

void OnlineReidOptions::check() const {
  if (decide_after < 1) throw UsageError("reid: --decide-after must be at least 1");
  if (max_wait_frames < 1) throw UsageError("reid: --max-wait must be at least 1 frame");
  if (max_scans < decide_after) throw UsageError("reid: max_scans must be at least --decide-after");
  if (!(min_quality >= 0 && min_quality <= 1)) throw UsageError("reid: --min-quality must be within 0..1");
  if (!(min_view_confidence >= 0 && min_view_confidence <= 1))
    throw UsageError("reid: --min-view-confidence must be within 0..1");
  if (!(update_gain >= 1)) throw UsageError("reid: update gain must be at least 1");
  if (update_every < 1) throw UsageError("reid: update_every must be at least 1");
  if (verify_every < 1 || strikes < 1) throw UsageError("reid: verify_every and strikes must be at least 1");
  if (!(verify_quality >= 0 && verify_quality <= 1)) throw UsageError("reid: verify_quality must be within 0..1");
  if (!(left_after_s >= 0)) throw UsageError("reid: --left-after must not be negative");
  if (std::isinf(threshold)) throw UsageError("reid: --threshold must be finite");
  if (!(margin >= 0)) throw UsageError("reid: --margin must not be negative");
  if (!(new_gap >= 0)) throw UsageError("reid: --new-gap must not be negative");
}

OnlineReid::OnlineReid(Gallery& gallery, const AppearanceMatcher& matcher, OnlineReidOptions options)
    : gallery_(gallery), matcher_(matcher), options_(std::move(options)) {
  options_.check();
  descriptor_ = matcher_.name() + "/" + matcher_.version();
  debug_ = std::getenv("BODYREC_REID_DEBUG") != nullptr;
  threshold_ = std::isnan(options_.threshold) ? matcher_.threshold() : options_.threshold;
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
  const GalleryEntry* stored = gallery_.find(user, view);
  return !stored || stored->descriptor != descriptor_ || quality > options_.update_gain * stored->quality;
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
  p.descriptor = matcher_.describe(PersonImage{body.scan->image, body.scan->mask});
  return p;
}

// Per user, the best similarity over the scans of the probe's view and its complementary views; users
// that have none of those are scored over all their views (a person seen from the front, now from the
// side, must still be found).
std::vector<OnlineReid::Score> OnlineReid::score_users(const Probe& probe) const {
  std::vector<View> near = complementary_views(probe.view);
  near.push_back(probe.view);
  std::map<UserId, Score> best_near, best_any;
  for (View v : kAllViews) {
    const bool is_near = options_.all_views || std::find(near.begin(), near.end(), v) != near.end();
    for (const GalleryEntry& e : gallery_.scans(v)) {
      if (e.descriptor != descriptor_) continue;
      const double s = matcher_.similarity(probe.descriptor, as_vector(e.features));
      for (auto* m : {is_near ? &best_near : nullptr, &best_any}) {
        if (!m) continue;
        auto it = m->find(e.user);
        if (it == m->end() || s > it->second.similarity) (*m)[e.user] = Score{e.user, s, v, m == &best_near};
      }
    }
  }
  std::vector<Score> out;
  for (const auto& [user, score] : best_any) {
    const auto it = best_near.find(user);
    out.push_back(it != best_near.end() ? it->second : score);
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

// Users held by another track seen in this frame: two bodies in one frame are two people.
std::vector<UserId> OnlineReid::users_held_except(uint64_t key) const {
  std::vector<UserId> held;
  for (const auto& [k, t] : tracks_)
    if (k != key && t.user && t.last_seen >= now_) held.push_back(*t.user);
  return held;
}

GalleryScan OnlineReid::gallery_scan(const Probe& probe) const {
  GalleryScan g;
  g.view = probe.view;
  g.image = probe.scan.image;
  g.mask = probe.scan.mask;
  g.features = cv::Mat(1, static_cast<int>(probe.descriptor.size()), CV_32F,
                       const_cast<float*>(probe.descriptor.data())).clone();
  g.descriptor = descriptor_;
  g.descriptor_version = 1;
  g.quality = probe.quality;
  return g;
}

void OnlineReid::log(const ReidEvent& event) {
  Event e;
  e.user = event.user;
  e.kind = store_kind(event.kind);
  e.score = event.score;
  e.view = event.view;
  e.track = static_cast<int64_t>(event.track);
  e.source = options_.source;
  gallery_.log_event(e);
}

void OnlineReid::enrol(uint64_t key, Track& track, std::vector<ReidEvent>& events) {
  // The best probe per view; the best of all is the enrolment scan.
  const std::map<View, const Probe*> best = best_per_view(track.probes, std::vector<bool>(track.probes.size(), true));
  const Probe* first = nullptr;
  for (const auto& [v, p] : best)
    if (!first || p->quality > first->quality) first = p;
  UserId user = 0;
  ++gallery_version_;
  gallery_.transaction([&] {
    user = gallery_.enrol(gallery_scan(*first), "", static_cast<int64_t>(key), options_.source);
    for (const auto& [v, p] : best)
      if (p != first) gallery_.put_scan(user, gallery_scan(*p));
  });
  events.push_back({ReidEventKind::kEnrolled, user, key, first->view, std::nullopt});
  for (const auto& [v, p] : best)
    if (p != first) {
      events.push_back({ReidEventKind::kViewAdded, user, key, v, std::nullopt});
      log(events.back());
    }
  track.user = user;
  track.last_verify = frame_;
}

void OnlineReid::decide(uint64_t key, Track& track, std::vector<ReidEvent>& events) {
  const std::vector<UserId> held = users_held_except(key);
  // Each scan votes: for the best user when it passes the threshold and stands out from the next one by
  // the margin; for "new" when even the best user is below the threshold by new_gap; not at all when
  // two users are too close to call or the best is in between.
  const double margin = options_.margin * std::abs(threshold_);
  const double new_gap = options_.new_gap * std::abs(threshold_);
  std::map<UserId, int> votes;
  std::map<UserId, double> sums;
  std::map<UserId, View> views;
  std::vector<int64_t> voted_for(track.probes.size(), -1);
  int for_new = 0;
  for (size_t i = 0; i < track.probes.size(); ++i) {
    std::vector<Score> s;
    for (const Score& x : scores(track.probes[i]))
      if (std::find(held.begin(), held.end(), x.user) == held.end()) s.push_back(x);
    if (debug_) {
      std::fprintf(stderr, "decide track %llu scan %zu view %s quality %.2f:", static_cast<unsigned long long>(key), i,
                   view_name(track.probes[i].view), track.probes[i].quality);
      for (const Score& x : s) std::fprintf(stderr, " u%lld %.3f(%s)", static_cast<long long>(x.user), x.similarity, view_name(x.view));
      std::fprintf(stderr, "\n");
    }
    // "New": nobody passes the threshold in a comparison of the same side of the body (same or
    // complementary view: reliable), or even the best is far below it (across views).
    if (s.empty() || s.front().similarity < threshold_ - new_gap || (s.front().near && s.front().similarity <= threshold_)) {
      ++for_new;
      continue;
    }
    if (s.front().similarity <= threshold_) continue;  // between "same" and "someone else": no vote
    if (s.size() > 1 && s[0].similarity - s[1].similarity < margin) continue;
    const UserId u = s.front().user;
    ++votes[u];
    sums[u] += s.front().similarity;
    views[u] = track.probes[i].view;
    voted_for[i] = u;
  }
  const int n = static_cast<int>(track.probes.size());
  UserId winner = 0;
  int most = 0;
  for (const auto& [u, k] : votes)
    if (k > most) winner = u, most = k;
  const bool forced = track.frames >= options_.max_wait_frames;
  if (2 * most > n || (forced && most > 0 && most >= for_new)) {
    track.user = winner;
    track.last_verify = frame_;
    events.push_back({ReidEventKind::kRecognised, winner, key, views[winner], sums[winner] / most});
    log(events.back());
    // A track that held this user but is not in this frame was the same body under an older key.
    for (auto& [k, t] : tracks_)
      if (k != key && t.user == winner) t.last_seen = -1e300;
    // The scans that voted for this user add the views it lacks (or improve them).
    std::vector<bool> voted(track.probes.size());
    for (size_t i = 0; i < voted.size(); ++i) voted[i] = voted_for[i] == winner;
    for (const auto& [v, p] : best_per_view(track.probes, voted)) {
      if (!improves(winner, v, p->quality)) continue;
      ++gallery_version_;
      if (gallery_.put_scan(winner, gallery_scan(*p)) == PutResult::kInserted) {
        events.push_back({ReidEventKind::kViewAdded, winner, key, v, std::nullopt});
        log(events.back());
      }
    }
  } else if (2 * for_new > n || (forced && for_new > 0 && for_new >= most) ||
             track.frames >= 3 * options_.max_wait_frames) {
    // (Scans that all fall between "same" and "someone else" wait three times longer before enrolling:
    // that is more often a known person half hidden or turned than a new one.)
    enrol(key, track, events);
  } else {
    return;  // undecided (too close to call, or contradicting scans): collect more
  }
  track.probes.clear();
}

void OnlineReid::update(uint64_t key, Track& track, const ReidBody& body, std::vector<ReidEvent>& events,
                        int& described) {
  if (!usable(body)) return;
  const UserId user = *track.user;
  const View view = *body.view.view;
  const bool better = improves(user, view, body.scan->quality);
  const bool verify = frame_ - track.last_verify >= options_.verify_every;
  if (!verify && !(better && frame_ - track.last_describe >= options_.update_every)) return;
  track.last_describe = frame_;
  std::optional<Probe> probe = describe(body);
  if (!probe) return;
  ++described;
  std::optional<Score> mine;
  double best_other = -std::numeric_limits<double>::infinity();
  for (const Score& s : score_users(*probe)) {
    if (s.user == user) mine = s;
    else best_other = std::max(best_other, s.similarity);
  }
  const double clear_miss = threshold_ - options_.new_gap * std::abs(threshold_);
  if (verify) {
    track.last_verify = frame_;
    // Only a comparison with the same or a complementary view can say "not this user": the other
    // side of a person may look different.
    if (debug_)
      std::fprintf(stderr, "verify track %llu user %lld view %s quality %.2f: %s %.3f (%s)\n", static_cast<unsigned long long>(key),
                   static_cast<long long>(user), view_name(view), probe->quality, mine && mine->near ? "near" : "far",
                   mine ? mine->similarity : 0.0, mine ? view_name(mine->view) : "-");
    if (mine && mine->near && probe->quality >= options_.verify_quality)
      track.strikes = mine->similarity < clear_miss ? track.strikes + 1 : 0;
    if (track.strikes >= options_.strikes) {
      // Not this user any more: release it and decide the body afresh from this scan on.
      events.push_back({ReidEventKind::kLeft, user, key, std::nullopt, std::nullopt});
      log(events.back());
      track.user.reset();
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
  ++gallery_version_;
  if (gallery_.put_scan(user, gallery_scan(*probe)) == PutResult::kInserted) {
    events.push_back({ReidEventKind::kViewAdded, user, key, view, std::nullopt});
    log(events.back());
  }
}

void OnlineReid::leave(uint64_t key, Track& track, std::vector<ReidEvent>& events) {
  if (!track.user && !track.probes.empty()) {
    track.frames = std::max(track.frames, options_.max_wait_frames);
    decide(key, track, events);
  }
  if (track.user) {
    events.push_back({ReidEventKind::kLeft, *track.user, key, std::nullopt, std::nullopt});
    log(events.back());
  }
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
  if (gallery_.refresh()) ++gallery_version_;
  for (const ReidBody& b : bodies) {
    Track& t = tracks_[b.track];
    t.last_seen = time_s;
    ++t.frames;
  }
  for (const ReidBody& b : bodies) {
    Track& t = tracks_[b.track];
    if (!t.user) {
      if (std::optional<Probe> p = describe(b)) {
        ++out.described;
        t.probes.push_back(std::move(*p));
        // Keep the evidence bounded: drop the poorest scan.
        if (t.probes.size() > static_cast<size_t>(options_.max_scans))
          t.probes.erase(std::min_element(t.probes.begin(), t.probes.end(),
                                          [](const Probe& a, const Probe& c) { return a.quality < c.quality; }));
      }
      const int n = static_cast<int>(t.probes.size());
      if (n >= options_.decide_after || (n > 0 && t.frames >= options_.max_wait_frames)) decide(b.track, t, out.events);
    } else {
      update(b.track, t, b, out.events, out.described);
    }
    out.identities.push_back({b.track, t.user, b.view.view, b.box});
  }
  for (auto it = tracks_.begin(); it != tracks_.end();) {
    if (it->second.last_seen < time_s - options_.left_after_s) {
      leave(it->first, it->second, out.events);
      it = tracks_.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

std::vector<ReidEvent> OnlineReid::finish() {
  std::vector<ReidEvent> events;
  for (auto& [key, track] : tracks_) leave(key, track, events);
  tracks_.clear();
  return events;
}

}  // namespace bodyrec
