#include "gallery_options.h"

#include <cstdio>

#include "bodyrec/core/error.h"

namespace bodyrec::cli {

void add_gallery_path_option(CLI::App& sub, GalleryCliOptions& options) {
  sub.add_option("--gallery", options.path,
                 "Gallery file (SQLite). Default: gallery.db in the working directory");
}

void add_gallery_write_options(CLI::App& sub, GalleryCliOptions& options) {
  sub.add_option("--gallery", options.path,
                 "Gallery file (SQLite, created mode 0600 when missing). Default: gallery.db in the working "
                 "directory");
  sub.add_flag("--no-images", options.no_images,
               "Store features only: no body images or masks are written to the gallery");
  sub.add_option("--prune-unseen-for", options.prune_unseen_for,
                 "Retention: at start, forget users not seen for this long (e.g. 30d, 12h)");
}

std::chrono::seconds parse_retention(const std::string& text, const char* option) {
  const auto d = parse_duration(text);
  if (!d)
    throw UsageError(std::string(option) + ": expected a whole number with s, m, h, d or w (e.g. 30d, 12h), got '" +
                     text + "'");
  return *d;
}

std::unique_ptr<Gallery> open_gallery_for_enrolment(const GalleryCliOptions& options) {
  std::optional<std::chrono::seconds> retention;
  if (!options.prune_unseen_for.empty()) retention = parse_retention(options.prune_unseen_for, "--prune-unseen-for");
  GalleryOptions o;
  o.create = true;
  o.store_images = !options.no_images;
  auto gallery = std::make_unique<Gallery>(options.path, o);
  if (retention) {
    const EraseReport r = gallery->prune_unseen(*retention);
    if (!r.users.empty())
      std::fprintf(stderr, "bodyrec: retention: forgot %zu users not seen for %s (%d scans, %d events)\n",
                   r.users.size(), options.prune_unseen_for.c_str(), r.scans, r.events);
  }
  return gallery;
}

}  // namespace bodyrec::cli
