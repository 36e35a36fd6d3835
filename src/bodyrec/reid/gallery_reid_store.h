// Online re-identification's people kept in a persistent Gallery (store/gallery.h), shared with other
// processes: `gallery forget`, `purge` and `prune` from another process while a run is open are taken in at
// the next refresh(); a write for a user erased meanwhile writes nothing (put_scan none, log false), so an
// erased user is never written back.
#pragma once

#include <optional>
#include <set>
#include <string>

#include "bodyrec/reid/appearance_matcher.h"
#include "bodyrec/reid/reid_store.h"
#include "bodyrec/store/gallery.h"

namespace bodyrec {

struct GalleryReidStoreOptions {
  std::string source;  // recording or camera name written with the events
  // The source's clock: event and scan times are start + the frame's seconds. None: the wall clock when
  // the write happens (a live source whose frame times are not wall times).
  std::optional<GalleryTime> start;
};

// Brings a gallery's scans that `matcher` cannot compare with up to date: another matcher's (a run with
// another --matcher), or another version of this one (another version() string, e.g. another learned
// model, or an older kReidDescriptorVersion layout). Each is described again from its stored image and
// mask (stature unknown) and replaced, in one transaction, so its user is still recognised. Returns how
// many were. Throws InputError naming the gallery when such a scan has no image (a gallery kept with
// --no-images): its features cannot be rebuilt, and its users would all be enrolled again; also for a
// layout newer than this build's.
int redescribe_old_scans(Gallery& gallery, const AppearanceMatcher& matcher);

class GalleryReidStore : public ReidStore {
 public:
  // Calls redescribe_old_scans (InputError as it says). `gallery` and `matcher` must outlive the store.
  GalleryReidStore(Gallery& gallery, const AppearanceMatcher& matcher, GalleryReidStoreOptions options = {});

  const std::vector<GalleryEntry>& scans(View view) const override { return gallery_.scans(view); }
  const GalleryEntry* find(UserId user, View view) const override { return gallery_.find(user, view); }
  UserId enrol(const std::vector<GalleryScan>& scans, uint64_t track, double time_s) override;
  std::optional<PutResult> put_scan(UserId user, const GalleryScan& scan, double time_s) override;
  bool log(const ReidEvent& event, double time_s) override;
  bool refresh() override;
  bool has_user(UserId user) const override { return users_.count(user) > 0; }
  // One gallery write transaction (Gallery::transaction: SQLite BEGIN IMMEDIATE, PostgreSQL the lock on
  // gallery_state's row), so refresh() inside it sees every commit of other processes and none can come
  // before it ends.
  void exclusive(const std::function<void()>& body) override { gallery_.transaction(body); }

 private:
  GalleryTime time_of(double time_s) const;
  bool exists(UserId user);  // asks the file (another process may have erased the user)
  void load_users();

  Gallery& gallery_;
  GalleryReidStoreOptions options_;
  std::set<UserId> users_;  // users with at least one scan in the cache
};

}  // namespace bodyrec
