// Online re-identification's people kept in memory only: nothing is written anywhere, everything is gone
// when the object is. For a run that must not store biometric data, and for testing the decisions without a
// database. forget() erases a user as another process's `gallery forget` would: writes for that user fail at
// once, and the cache (what the decisions read) drops the user at the next refresh().
#pragma once

#include <array>
#include <map>
#include <vector>

#include "bodyrec/reid/reid_store.h"

namespace bodyrec {

class MemoryReidStore : public ReidStore {
 public:
  struct LoggedEvent {
    ReidEvent event;
    double time_s = 0;
  };

  const std::vector<GalleryEntry>& scans(View view) const override { return cache_[static_cast<int>(view)]; }
  const GalleryEntry* find(UserId user, View view) const override;
  UserId enrol(const std::vector<GalleryScan>& scans, uint64_t track, double time_s) override;
  std::optional<PutResult> put_scan(UserId user, const GalleryScan& scan, double time_s) override;
  bool log(const ReidEvent& event, double time_s) override;
  bool refresh() override;
  bool has_user(UserId user) const override;

  // Erases the user's events at once and the user's scans at the next refresh(). False when there is no
  // such user.
  bool forget(UserId user);
  const std::vector<LoggedEvent>& events() const { return events_; }
  int user_count() const;

 private:
  void erase_from_cache(UserId user);
  bool alive(UserId user) const;  // not forgotten

  std::array<std::vector<GalleryEntry>, kViewCount> cache_;
  std::map<UserId, bool> users_;  // every id given out; false once forgotten
  std::vector<UserId> forgotten_; // not yet dropped from the cache
  std::vector<LoggedEvent> events_;
  UserId next_ = 1;
};

}  // namespace bodyrec
