#include "bodyrec/reid/track_segments.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include "bodyrec/core/error.h"

namespace bodyrec {

void TrackSegmentOptions::check() const {
  if (!(cut_gap >= 0)) throw OptionError("TrackSegmentOptions", "cut_gap", "must be >= 0");
  if (strikes < 1) throw OptionError("TrackSegmentOptions", "strikes", "must be >= 1");
  if (references < 1) throw OptionError("TrackSegmentOptions", "references", "must be >= 1");
  if (join_within < 0) throw OptionError("TrackSegmentOptions", "join_within", "must be >= 0");
  if (!(join_gap >= 0)) throw OptionError("TrackSegmentOptions", "join_gap", "must be >= 0");
  if (!(margin >= 0)) throw OptionError("TrackSegmentOptions", "margin", "must be >= 0");
  if (forget_after < 1) throw OptionError("TrackSegmentOptions", "forget_after", "must be >= 1");
  if (!(min_quality >= 0 && min_quality <= 1)) throw OptionError("TrackSegmentOptions", "min_quality", "must be in 0..1");
}

TrackSegments::TrackSegments(const AppearanceMatcher& matcher, const TrackSegmentOptions& options)
    : matcher_(matcher), options_((options.check(), options)) {
  const double t = matcher_.threshold();
  cut_below_ = t - options_.cut_gap * std::abs(t);
}

uint64_t TrackSegments::key(uint64_t track, const PartialScan* scan) {
  auto [it, added] = segments_.try_emplace(track);
  Segment& s = it->second;
  if (added) s.key = track;
  s.seen = frame_;
  if (!options_.enabled || !scan || scan->quality < options_.min_quality) return s.key;
  std::vector<float> d = matcher_.describe(PersonImage{scan->image, scan->mask, scan->row_height_m});
  if (s.references.empty() && s.cuts == 0 && !s.joinable) {
    if (Segment* old = continued(track, d)) {
      // The same person under a new tracker id: their key and references move here.
      s.key = old->key;
      s.references = std::move(old->references);
      s.strikes = 0;
      old->references.clear();
      old->key = (old->key & 0xffffffffu) + (++old->cuts << 32);
      old->joinable = false;
      ++joins_;
    }
  }
  s.joinable = true;
  if (!s.references.empty()) {
    double best = -std::numeric_limits<double>::infinity();
    for (const std::vector<float>& r : s.references) best = std::max(best, matcher_.similarity(d, r));
    if (best < cut_below_) {
      if (++s.strikes >= options_.strikes) {
        // Someone else: a new key, references from this scan on.
        s.key = track + (++s.cuts << 32);
        s.strikes = 0;
        s.references.clear();
        ++cuts_;
      } else {
        return s.key;  // a strike teaches nothing
      }
    } else {
      s.strikes = 0;
    }
  }
  s.references.push_back(std::move(d));
  if (s.references.size() > static_cast<size_t>(options_.references)) s.references.pop_front();
  return s.key;
}

TrackSegments::Segment* TrackSegments::continued(uint64_t track, const std::vector<float>& d) {
  if (options_.join_within <= 0) return nullptr;
  const double t = matcher_.threshold();
  Segment* best = nullptr;
  double first = -std::numeric_limits<double>::infinity(), second = first;
  for (auto& [id, o] : segments_) {
    if (id == track || !o.joinable || o.references.empty() || frame_ - o.seen < 2 || frame_ - o.seen > options_.join_within)
      continue;
    double sim = -std::numeric_limits<double>::infinity();
    for (const std::vector<float>& r : o.references) sim = std::max(sim, matcher_.similarity(d, r));
    if (sim > first) {
      second = first, first = sim, best = &o;
    } else {
      second = std::max(second, sim);
    }
  }
  if (!best || first < t + options_.join_gap * std::abs(t) || first - second < options_.margin * std::abs(t)) return nullptr;
  return best;
}

void TrackSegments::next_frame() {
  ++frame_;
  for (auto it = segments_.begin(); it != segments_.end();)
    it = frame_ - it->second.seen > options_.forget_after ? segments_.erase(it) : std::next(it);
}

}  // namespace bodyrec
