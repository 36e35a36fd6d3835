// Where online re-identification keeps the people it knows: what its decisions read (every stored scan's
// features, GalleryCache) and the writes they make. OnlineReid knows nothing else of storage:
//  - GalleryReidStore (gallery_reid_store.h) keeps them in a persistent Gallery shared with other processes;
//  - MemoryReidStore (memory_reid_store.h) keeps them in memory, for a run that must store nothing.
// Times are the source's seconds (RgbdFrame::time_s); a store turns them into its own clock.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "bodyrec/reid/reid_event.h"
#include "bodyrec/store/gallery_cache.h"

namespace bodyrec {

class ReidStore : public GalleryCache {
 public:
  // A new user with `scans` (each of another view; the first is the enrolment scan) and an `enrolled`
  // event, written together. Returns the new user's id (ids are never reused).
  virtual UserId enrol(const std::vector<GalleryScan>& scans, uint64_t track, double time_s) = 0;
  // Keeps the user's best scan per view (Gallery::put_scan). None when the user no longer exists (erased
  // meanwhile): nothing is written.
  virtual std::optional<PutResult> put_scan(UserId user, const GalleryScan& scan, double time_s) = 0;
  // Records a recognised / view_added / left event. False when the user no longer exists: nothing is written.
  virtual bool log(const ReidEvent& event, double time_s) = 0;
  // Takes in what other writers changed since the last call (new users and views, erasures). True when
  // anything changed: the cache then holds the new state.
  virtual bool refresh() = 0;
  // Whether the user exists in the cache (false once erased and refreshed).
  virtual bool has_user(UserId user) const = 0;
  // Runs `body` with every other writer of the store kept out until it ends; its writes commit together
  // (or none, when it throws). A refresh() inside it takes in everything others committed before, and
  // nobody can add to that until it ends: an enrolment decided inside it is decided against every user
  // there is (two sensors meeting one new person make one user). A store no other process writes (memory)
  // just runs it.
  virtual void exclusive(const std::function<void()>& body) { body(); }
};

}  // namespace bodyrec
