// The gallery's scans of one matcher, indexed per view (DescriptorIndex) so that a probe is scored
// against every stored scan without copying them: what OnlineReid searches for each new scan.
//
// The index follows the gallery's in-memory cache, and the caller keeps it in step: reload() after the
// cache reloaded (another process wrote the file), update(user) after writing or erasing that user's
// scans. Users get dense slots (stable while the index lives) so a search can be tallied in arrays.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <vector>

#include "bodyrec/reid/appearance_matcher.h"
#include "bodyrec/store/gallery_cache.h"

namespace bodyrec {

class GalleryIndex {
 public:
  // `accept` says which scans count (the matcher's, in the current layout); `descriptor` gives a scan's
  // descriptor as the matcher compares it. `gallery` and `matcher` must outlive the index.
  GalleryIndex(const GalleryCache& gallery, const AppearanceMatcher& matcher,
               std::function<bool(const GalleryEntry&)> accept,
               std::function<DescriptorView(const GalleryEntry&)> descriptor);

  void reload();              // everything again from the gallery's cache
  void update(UserId user);   // that user's scans again (removed when the gallery has none)

  // out[i] = similarity(probe, i-th indexed scan of `view`), whose user has slot slots(view)[i].
  void search(View view, DescriptorView probe, std::vector<double>& out) const;
  const std::vector<uint32_t>& slots(View view) const { return views_[static_cast<int>(view)].slots; }
  UserId user(uint32_t slot) const { return users_.at(slot); }
  size_t slot_count() const { return users_.size(); }  // users ever indexed (erased ones leave a gap)
  size_t size() const;        // indexed scans

 private:
  struct ViewRows {
    std::unique_ptr<DescriptorIndex> rows;
    std::vector<uint32_t> slots;  // per row
  };
  uint32_t slot_of(UserId user);
  void put(ViewRows& view, uint32_t slot, const GalleryEntry* entry);

  const GalleryCache& gallery_;
  const AppearanceMatcher& matcher_;
  std::function<bool(const GalleryEntry&)> accept_;
  std::function<DescriptorView(const GalleryEntry&)> descriptor_;
  std::array<ViewRows, kViewCount> views_;
  std::vector<UserId> users_;            // by slot
  std::map<UserId, uint32_t> slot_;      // by user
};

}  // namespace bodyrec
