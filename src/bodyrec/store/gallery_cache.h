// The in-memory view of a gallery that matching reads: every stored scan's features per view, no pixels,
// no database access. `Gallery` keeps one in step with its file; re-identification's decision code reads
// only this (reid/reid_store.h), so it can run on a gallery held in memory as well.
#pragma once

#include <vector>

#include "bodyrec/store/gallery_types.h"

namespace bodyrec {

class GalleryCache {
 public:
  virtual ~GalleryCache() = default;
  // Every stored scan of `view` (at most one per user). The reference stays valid; its contents change
  // with the owner's next write or reload.
  virtual const std::vector<GalleryEntry>& scans(View view) const = 0;
  // One user's scan of `view`, or nullptr.
  virtual const GalleryEntry* find(UserId user, View view) const = 0;
};

}  // namespace bodyrec
