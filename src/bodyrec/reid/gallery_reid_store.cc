#include "bodyrec/reid/gallery_reid_store.h"

#include <algorithm>

#include <opencv2/imgcodecs.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/reid_features.h"

namespace bodyrec {
namespace {

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

int redescribe_old_scans(Gallery& gallery, const AppearanceMatcher& matcher) {
  const std::string descriptor = matcher.name() + "/" + matcher.version();
  // Scans this matcher cannot compare with: another matcher's, or made by another version of this one (its
  // descriptor, its model, or the layout). Left as they are, their users would all be enrolled again.
  const auto stale = [&](const std::string& d, int version) {
    if (d == descriptor && version > kReidDescriptorVersion)
      throw InputError(gallery.path() + ": scans of " + d + " in layout version " + std::to_string(version) +
                       ", newer than this bodyrec's " + std::to_string(kReidDescriptorVersion) + ": use a newer bodyrec");
    return d != descriptor || version != kReidDescriptorVersion;
  };
  std::vector<UserId> users;
  for (View v : kAllViews)
    for (const GalleryEntry& e : gallery.scans(v))
      if (stale(e.descriptor, e.descriptor_version) && std::find(users.begin(), users.end(), e.user) == users.end())
        users.push_back(e.user);
  if (users.empty()) return 0;
  std::vector<std::pair<UserId, StoredScan>> old;
  for (UserId u : users)
    for (StoredScan& s : gallery.user_scans(u))
      if (stale(s.descriptor, s.descriptor_version)) old.emplace_back(u, std::move(s));
  for (const auto& [u, s] : old)
    if (s.image_png.empty())
      throw InputError(gallery.path() + ": " + std::to_string(old.size()) + " scans (user " + std::to_string(u) +
                       " among them) hold " + s.descriptor + " features (layout " + std::to_string(s.descriptor_version) +
                       "); this run describes with " + descriptor + " (layout " +
                       std::to_string(kReidDescriptorVersion) +
                       ") and they have no image to describe again (kept with --no-images): run with the matcher that made "
                       "them, forget those users (bodyrec gallery forget USER) or start a new gallery");
  gallery.transaction([&] {
    for (const auto& [u, s] : old) {
      const cv::Mat image = cv::imdecode(s.image_png, cv::IMREAD_COLOR);
      cv::Mat mask = s.mask_png.empty() ? cv::Mat() : cv::imdecode(s.mask_png, cv::IMREAD_GRAYSCALE);
      if (image.empty() || (!mask.empty() && mask.size() != image.size()))
        throw InputError(gallery.path() + ": user " + std::to_string(u) + " view " + view_name(s.view) +
                         ": the stored image or mask cannot be decoded");
      GalleryScan g;
      g.view = s.view;
      g.image = image;
      g.mask = mask;
      g.features = reid_features(matcher.describe(PersonImage{image, mask}), std::nullopt, 0);
      g.descriptor = descriptor;
      g.descriptor_version = kReidDescriptorVersion;
      g.quality = s.quality;
      g.time = s.time;
      gallery.put_scan(u, g);
    }
  });
  return static_cast<int>(old.size());
}

GalleryReidStore::GalleryReidStore(Gallery& gallery, const AppearanceMatcher& matcher, GalleryReidStoreOptions options)
    : gallery_(gallery), options_(std::move(options)) {
  redescribe_old_scans(gallery_, matcher);
  load_users();
}

void GalleryReidStore::load_users() {
  users_.clear();
  for (View v : kAllViews)
    for (const GalleryEntry& e : gallery_.scans(v)) users_.insert(e.user);
}

GalleryTime GalleryReidStore::time_of(double time_s) const {
  if (!options_.start) return GalleryClock::now();
  return *options_.start + std::chrono::duration_cast<GalleryClock::duration>(std::chrono::duration<double>(time_s));
}

bool GalleryReidStore::exists(UserId user) { return gallery_.user(user).has_value(); }

UserId GalleryReidStore::enrol(const std::vector<GalleryScan>& scans, uint64_t track, double time_s) {
  if (scans.empty()) throw ProcessingError(gallery_.path() + ": an enrolment needs a scan");
  const GalleryTime t = time_of(time_s);
  UserId user = 0;
  gallery_.transaction([&] {
    GalleryScan first = scans.front();
    first.time = t;
    user = gallery_.enrol(first, "", static_cast<int64_t>(track), options_.source);
    for (size_t i = 1; i < scans.size(); ++i) {
      GalleryScan s = scans[i];
      s.time = t;
      gallery_.put_scan(user, s);
    }
  });
  users_.insert(user);
  return user;
}

std::optional<PutResult> GalleryReidStore::put_scan(UserId user, const GalleryScan& scan, double time_s) {
  GalleryScan s = scan;
  s.time = time_of(time_s);
  try {
    return gallery_.put_scan(user, s);
  } catch (const InputError&) {
    if (exists(user)) throw;
    users_.erase(user);  // erased by another process since the last refresh
    return std::nullopt;
  }
}

bool GalleryReidStore::log(const ReidEvent& event, double time_s) {
  Event e;
  e.user = event.user;
  e.kind = store_kind(event.kind);
  e.score = event.score;
  e.view = event.view;
  e.time = time_of(time_s);
  e.track = static_cast<int64_t>(event.track);
  e.source = options_.source;
  try {
    gallery_.log_event(e);
    return true;
  } catch (const InputError&) {
    if (exists(event.user)) throw;
    users_.erase(event.user);
    return false;
  }
}

bool GalleryReidStore::refresh() {
  if (!gallery_.refresh()) return false;
  load_users();
  return true;
}

}  // namespace bodyrec
