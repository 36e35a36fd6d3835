// Opening a gallery: the backend for the location (file or postgresql:// URI), schema checks and
// migration, the feature cache and transactions. Writes are in gallery_write.cc, reads in gallery_read.cc.
#include "bodyrec/store/gallery.h"

#include <algorithm>

#include "bodyrec/core/error.h"
#include "bodyrec/store/feature_blob.h"
#include "bodyrec/store/gallery_backend.h"
#include "bodyrec/store/postgres.h"
#include "bodyrec/store/schema.h"

namespace bodyrec {

void GalleryOptions::check() const {
  if (create && read_only) throw OptionError("GalleryOptions", "create", "cannot be combined with read_only");
  if (busy_timeout_ms < 0) throw OptionError("GalleryOptions", "busy_timeout_ms", "must be >= 0");
  if (max_events_per_user < 0) throw OptionError("GalleryOptions", "max_events_per_user", "must be >= 0 (0 = all)");
}

Gallery::Gallery(const std::string& path, const GalleryOptions& options) : path_(path), options_(options) {
  options_.check();
  backend_ = sql::is_postgres_uri(path) ? store::make_postgres_backend(path, options_)
                                        : store::make_sqlite_backend(path, options_);
  db_ = &backend_->connection();
  migrate();
  load_cache();
}

Gallery::~Gallery() = default;

void Gallery::migrate() {
  auto stamp = backend_->stamp();
  if (!stamp.empty && !stamp.ours)
    throw InputError(path_ + ": " + backend_->database_kind() + ", but not a bodyrec gallery");
  if (stamp.version > kGallerySchemaVersion)
    throw InputError(path_ + ": gallery schema version " + std::to_string(stamp.version) +
                     " is newer than this bodyrec reads (up to " + std::to_string(kGallerySchemaVersion) +
                     "); use a newer bodyrec");
  if (stamp.version == kGallerySchemaVersion) return;
  if (stamp.empty && !options_.create) throw InputError(path_ + ": " + backend_->empty_kind() + ", not a bodyrec gallery");
  if (options_.read_only)
    throw InputError(path_ + ": gallery schema version " + std::to_string(stamp.version) + " needs an upgrade to " +
                     std::to_string(kGallerySchemaVersion) + "; open it once for writing (bodyrec gallery init)");
  backend_->begin_upgrade();
  try {
    // Another process may have upgraded it while this one waited for the lock.
    stamp = backend_->stamp();
    for (int v = stamp.version; v < kGallerySchemaVersion; ++v) {
      db_->exec(store::schema_step(db_->dialect(), v));
      backend_->set_version(v + 1);
    }
    backend_->commit();
  } catch (...) {
    db_->rollback_quietly();
    throw;
  }
}

void Gallery::load_cache() {
  for (auto& view : cache_) view.clear();
  // The counter first: a write committed during the load makes the next refresh() load again.
  backend_->may_have_changed();
  scan_changes_ = read_scan_changes();
  sql::Statement s(*db_,
                   "SELECT \"user\", view, features, descriptor, descriptor_version, quality FROM scans "
                   "ORDER BY \"user\", view");
  while (s.step()) {
    GalleryEntry e;
    e.user = s.column_int(0);
    e.view = static_cast<View>(s.column_int(1));
    e.features = store::decode_features(s.column_blob_data(2), s.column_bytes(2),
                                        path_ + ": user " + std::to_string(e.user));
    e.descriptor = s.column_text(3);
    e.descriptor_version = static_cast<int>(s.column_int(4));
    e.quality = s.column_double(5);
    cache_[static_cast<int>(e.view)].push_back(std::move(e));
  }
  cache_dirty_ = false;
}

int64_t Gallery::read_scan_changes() { return db_->query_int("SELECT scan_changes FROM gallery_state"); }

bool Gallery::refresh() {
  if (!cache_dirty_ && (!backend_->may_have_changed() || read_scan_changes() == scan_changes_)) return false;
  load_cache();
  return true;
}

void Gallery::scans_changed() {
  if (txn_scan_changes_) return;
  sql::Statement s(*db_, "UPDATE gallery_state SET scan_changes = scan_changes + 1 RETURNING scan_changes");
  if (!s.step()) throw ProcessingError(path_ + ": gallery_state has no row");
  txn_scan_changes_ = s.column_int(0);
  s.reset();
  // Writers take turns (begin_write), so the count moved by this transaction alone when it is one more
  // than the cache's: the cache, which takes this transaction's writes, is then current after the commit.
  txn_cache_was_current_ = *txn_scan_changes_ == scan_changes_ + 1;
}

void Gallery::cache_put(const GalleryEntry& entry) {
  auto& view = cache_[static_cast<int>(entry.view)];
  for (auto& e : view)
    if (e.user == entry.user) {
      e = entry;
      return;
    }
  view.push_back(entry);
}

const GalleryEntry* Gallery::find(UserId user, View view) const {
  for (const auto& e : cache_[static_cast<int>(view)])
    if (e.user == user) return &e;
  return nullptr;
}

void Gallery::cache_erase(UserId user) {
  for (auto& view : cache_)
    view.erase(std::remove_if(view.begin(), view.end(), [&](const GalleryEntry& e) { return e.user == user; }),
               view.end());
}

std::string Gallery::integrity_check() { return backend_->integrity_check(); }

void Gallery::begin() {
  if (options_.read_only) throw ProcessingError(path_ + ": gallery opened read-only, cannot write");
  if (depth_++ == 0) {
    aborted_ = false;
    txn_scan_changes_.reset();
    try {
      backend_->begin_write();
    } catch (...) {
      depth_ = 0;
      throw;
    }
  }
}

void Gallery::commit() {
  if (--depth_ > 0) return;
  if (aborted_) {
    rollback_now();
    throw ProcessingError(path_ + ": transaction rolled back after a failed write inside it");
  }
  try {
    backend_->commit();
  } catch (...) {
    rollback_now();
    throw;
  }
  if (txn_scan_changes_) {
    if (txn_cache_was_current_) scan_changes_ = *txn_scan_changes_;
    else cache_dirty_ = true;  // another process changed scans before: refresh() loads them
    txn_scan_changes_.reset();
  }
}

void Gallery::rollback() {
  if (--depth_ > 0) {
    aborted_ = true;
    return;
  }
  rollback_now();
}

void Gallery::rollback_now() {
  db_->rollback_quietly();
  // The cache took the rolled-back writes; reload it from the database. The connection may be gone
  // (PostgreSQL restart): the caller's error says so; a stale cache is marked for the next refresh.
  try {
    load_cache();
  } catch (const Error&) {
    cache_dirty_ = true;
  }
}

}  // namespace bodyrec
