#include "bodyrec/store/schema.h"

#include <array>

#include "bodyrec/core/error.h"
#include "bodyrec/store/gallery.h"
#include "bodyrec/store/sqlite.h"

namespace bodyrec::store {

namespace {

// Version 0 -> 1: the first schema. Times are integer milliseconds since the Unix epoch (UTC); a view
// is View's numeric value (reid/view.h). A later version adds an entry `kSteps[1]` ("1 -> 2") with its
// ALTER TABLE statements; files are upgraded one step at a time, so every old version keeps working.
constexpr const char* kV1 = R"sql(
CREATE TABLE users(
  id INTEGER PRIMARY KEY AUTOINCREMENT,  -- AUTOINCREMENT: a forgotten user's id is never reused
  label TEXT NOT NULL DEFAULT '',
  created_ms INTEGER NOT NULL,
  first_seen_ms INTEGER NOT NULL,
  last_seen_ms INTEGER NOT NULL);
CREATE INDEX users_last_seen ON users(last_seen_ms);
CREATE TABLE scans(
  id INTEGER PRIMARY KEY,
  user INTEGER NOT NULL REFERENCES users(id) ON DELETE CASCADE,
  view INTEGER NOT NULL CHECK (view BETWEEN 0 AND 7),
  features BLOB NOT NULL,
  descriptor TEXT NOT NULL,
  descriptor_version INTEGER NOT NULL,
  quality REAL NOT NULL,
  time_ms INTEGER NOT NULL,
  -- Pixels last: loading the feature cache reads a row only up to `quality` and never walks the
  -- images' overflow pages.
  image_png BLOB,
  mask_png BLOB,
  UNIQUE (user, view));
CREATE TABLE events(
  id INTEGER PRIMARY KEY,
  user INTEGER REFERENCES users(id) ON DELETE CASCADE,  -- NULL for forgotten/pruned records
  kind TEXT NOT NULL,
  score REAL,
  view INTEGER CHECK (view BETWEEN 0 AND 7),
  time_ms INTEGER NOT NULL,
  track INTEGER,
  source TEXT NOT NULL DEFAULT '');
CREATE INDEX events_user ON events(user, id);
PRAGMA application_id = 1651664689;
PRAGMA user_version = 1;
)sql";

constexpr std::array<const char*, kGallerySchemaVersion> kSteps = {kV1};

}  // namespace

void upgrade_schema(sql::Database& db, int from) {
  for (int v = from; v < kGallerySchemaVersion; ++v) db.exec(kSteps.at(static_cast<size_t>(v)));
}

}  // namespace bodyrec::store
