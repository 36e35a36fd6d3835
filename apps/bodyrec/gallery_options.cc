#include "gallery_options.h"

#include "bodyrec/core/error.h"

namespace bodyrec::cli {

void add_gallery_path_option(CLI::App& sub, GalleryCliOptions& options) {
  sub.add_option("--gallery", options.path,
                 "Gallery: an SQLite file, or a PostgreSQL database as a libpq URI postgresql://[ROLE@]HOST[:PORT]/DB"
                 "[?sslmode=verify-full...] (the password comes from PGPASSFILE or ~/.pgpass, never the URI). "
                 "Default: gallery.db in the working directory");
}

std::chrono::seconds parse_retention(const std::string& text, const char* option) {
  const auto d = parse_duration(text);
  if (!d)
    throw UsageError(std::string(option) + ": expected a whole number with s, m, h, d or w (e.g. 30d, 12h), got '" +
                     text + "'");
  return *d;
}

}  // namespace bodyrec::cli
