#include "bodyrec/reid/memory_reid_store.h"

#include <algorithm>

#include "bodyrec/core/error.h"

namespace bodyrec {

const GalleryEntry* MemoryReidStore::find(UserId user, View view) const {
  for (const GalleryEntry& e : cache_[static_cast<int>(view)])
    if (e.user == user) return &e;
  return nullptr;
}

bool MemoryReidStore::has_user(UserId user) const {
  const auto it = users_.find(user);
  if (it == users_.end()) return false;
  return it->second || std::find(forgotten_.begin(), forgotten_.end(), user) != forgotten_.end();
}

bool MemoryReidStore::alive(UserId user) const {
  const auto it = users_.find(user);
  return it != users_.end() && it->second;
}

int MemoryReidStore::user_count() const {
  return static_cast<int>(std::count_if(users_.begin(), users_.end(), [](const auto& u) { return u.second; }));
}

UserId MemoryReidStore::enrol(const std::vector<GalleryScan>& scans, uint64_t track, double time_s) {
  if (scans.empty()) throw ProcessingError("reid: an enrolment needs a scan");
  const UserId user = next_++;
  users_[user] = true;
  for (const GalleryScan& s : scans) put_scan(user, s, time_s);
  events_.push_back({{ReidEventKind::kEnrolled, user, track, scans.front().view, std::nullopt}, time_s});
  return user;
}

std::optional<PutResult> MemoryReidStore::put_scan(UserId user, const GalleryScan& scan, double) {
  if (!alive(user)) return std::nullopt;
  if (scan.features.empty()) throw ProcessingError("reid: a scan without features");
  GalleryEntry entry;
  entry.user = user;
  entry.view = scan.view;
  entry.features = scan.features.clone();
  entry.descriptor = scan.descriptor;
  entry.descriptor_version = scan.descriptor_version;
  entry.quality = scan.quality;
  std::vector<GalleryEntry>& view = cache_[static_cast<int>(scan.view)];
  for (GalleryEntry& e : view)
    if (e.user == user) {
      // As Gallery::put_scan: a better scan, or one of another descriptor, replaces the stored one.
      if (scan.quality > e.quality || e.descriptor != scan.descriptor || e.descriptor_version != scan.descriptor_version) {
        e = entry;
        return PutResult::kReplaced;
      }
      return PutResult::kKept;
    }
  view.push_back(entry);
  return PutResult::kInserted;
}

bool MemoryReidStore::log(const ReidEvent& event, double time_s) {
  if (!alive(event.user)) return false;
  events_.push_back({event, time_s});
  return true;
}

bool MemoryReidStore::forget(UserId user) {
  if (!alive(user)) return false;
  users_[user] = false;
  forgotten_.push_back(user);
  events_.erase(std::remove_if(events_.begin(), events_.end(), [&](const LoggedEvent& e) { return e.event.user == user; }),
                events_.end());
  return true;
}

void MemoryReidStore::erase_from_cache(UserId user) {
  for (auto& view : cache_)
    view.erase(std::remove_if(view.begin(), view.end(), [&](const GalleryEntry& e) { return e.user == user; }), view.end());
}

bool MemoryReidStore::refresh() {
  if (forgotten_.empty()) return false;
  for (UserId user : forgotten_) erase_from_cache(user);
  forgotten_.clear();
  return true;
}

}  // namespace bodyrec
