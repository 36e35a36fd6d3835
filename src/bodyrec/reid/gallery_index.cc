#include "bodyrec/reid/gallery_index.h"

#include <algorithm>

namespace bodyrec {

GalleryIndex::GalleryIndex(const GalleryCache& gallery, const AppearanceMatcher& matcher,
                           std::function<bool(const GalleryEntry&)> accept,
                           std::function<DescriptorView(const GalleryEntry&)> descriptor)
    : gallery_(gallery), matcher_(matcher), accept_(std::move(accept)), descriptor_(std::move(descriptor)) {
  reload();
}

void GalleryIndex::reload() {
  for (View v : kAllViews) {
    ViewRows& view = views_[static_cast<int>(v)];
    view.rows = matcher_.make_index();
    view.slots.clear();
    for (const GalleryEntry& e : gallery_.scans(v))  // one scan per user and view: no row to look up
      if (accept_(e)) {
        view.rows->push_back(descriptor_(e));
        view.slots.push_back(slot_of(e.user));
      }
  }
}

void GalleryIndex::update(UserId user) {
  const uint32_t slot = slot_of(user);
  for (View v : kAllViews) {
    const GalleryEntry* e = gallery_.find(user, v);
    put(views_[static_cast<int>(v)], slot, e && accept_(*e) ? e : nullptr);
  }
}

// Sets, adds or (entry null) removes the row of `slot`.
void GalleryIndex::put(ViewRows& view, uint32_t slot, const GalleryEntry* entry) {
  const auto it = std::find(view.slots.begin(), view.slots.end(), slot);
  const size_t row = static_cast<size_t>(it - view.slots.begin());
  if (!entry) {
    if (it == view.slots.end()) return;
    view.rows->swap_remove(row);
    view.slots[row] = view.slots.back();
    view.slots.pop_back();
  } else if (it == view.slots.end()) {
    view.rows->push_back(descriptor_(*entry));
    view.slots.push_back(slot);
  } else {
    view.rows->set(row, descriptor_(*entry));
  }
}

uint32_t GalleryIndex::slot_of(UserId user) {
  const auto [it, added] = slot_.emplace(user, static_cast<uint32_t>(users_.size()));
  if (added) users_.push_back(user);
  return it->second;
}

void GalleryIndex::search(View view, DescriptorView probe, std::vector<double>& out) const {
  views_[static_cast<int>(view)].rows->similarities(probe, out);
}

size_t GalleryIndex::size() const {
  size_t n = 0;
  for (const ViewRows& v : views_) n += v.slots.size();
  return n;
}

}  // namespace bodyrec
