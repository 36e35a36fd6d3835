// Opening a gallery: file creation with private permissions, connection settings, schema checks and
// migration, and the feature cache. Writes are in gallery_write.cc, reads in gallery_read.cc.
#include "bodyrec/store/gallery.h"

#include <fcntl.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

#include "bodyrec/core/error.h"
#include "bodyrec/store/feature_blob.h"
#include "bodyrec/store/schema.h"
#include "bodyrec/store/sqlite.h"

namespace bodyrec {

namespace {

// Creates an empty file readable and writable by its owner only. The umask can only remove bits from
// open()'s mode, so fchmod sets 0600 exactly. An empty file is a valid empty SQLite database; EEXIST
// (another process created it first) is fine.
void create_private_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    if (errno == EEXIST) return;
    throw InputError(path + ": cannot create gallery: " + std::strerror(errno));
  }
  const int rc = ::fchmod(fd, 0600);
  const int saved = errno;
  ::close(fd);
  if (rc != 0) throw ProcessingError(path + ": cannot set mode 0600: " + std::strerror(saved));
}

}  // namespace

void GalleryOptions::check() const {
  if (create && read_only) throw UsageError("gallery: create and read-only cannot be combined");
  if (busy_timeout_ms < 0) throw UsageError("gallery: busy timeout must be >= 0 ms");
  if (max_events_per_user < 0) throw UsageError("gallery: the events kept per user must be >= 0 (0 = all)");
}

Gallery::Gallery(const std::string& path, const GalleryOptions& options) : path_(path), options_(options) {
  options_.check();
  std::error_code ec;
  const bool exists = std::filesystem::exists(path, ec);
  if (!exists) {
    if (!options_.create) throw InputError(path + ": gallery not found");
    create_private_file(path);
  } else if (std::filesystem::is_directory(path, ec)) {
    throw InputError(path + ": is a directory, not a gallery file");
  }
  // A read-only gallery is still opened read-write when the file allows it, with query_only set: only a
  // writable connection can checkpoint and remove the -wal/-shm files when it closes.
  const bool writable = ::access(path.c_str(), W_OK) == 0;
  db_ = std::make_unique<sql::Database>(
      path, options_.read_only && !writable ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE);
  if (options_.read_only) db_->exec("PRAGMA query_only = ON");
  configure_connection();
  migrate();
  load_cache();
}

Gallery::~Gallery() = default;

void Gallery::configure_connection() {
  sqlite3_busy_timeout(db_->handle(), options_.busy_timeout_ms);
  // The first read of the header: a file that is not SQLite fails here with SQLITE_NOTADB (InputError).
  db_->query_int("PRAGMA user_version");
  db_->exec("PRAGMA foreign_keys = ON");
  // Deleted rows (forget, purge, replaced scans) are overwritten with zeros, not just unlinked.
  db_->exec("PRAGMA secure_delete = ON");
  if (options_.read_only) return;
  db_->exec("PRAGMA journal_mode = WAL");
  db_->exec(options_.sync_full ? "PRAGMA synchronous = FULL" : "PRAGMA synchronous = NORMAL");
}

void Gallery::migrate() {
  auto version = static_cast<int>(db_->query_int("PRAGMA user_version"));
  const int64_t app = db_->query_int("PRAGMA application_id");
  const int64_t objects = db_->query_int("SELECT count(*) FROM sqlite_master");
  const bool empty = version == 0 && app == 0 && objects == 0;
  if (!empty && app != store::kGalleryApplicationId)
    throw InputError(path_ + ": an SQLite database, but not a bodyrec gallery");
  if (version > kGallerySchemaVersion)
    throw InputError(path_ + ": gallery schema version " + std::to_string(version) +
                     " is newer than this bodyrec reads (up to " + std::to_string(kGallerySchemaVersion) +
                     "); use a newer bodyrec");
  if (version == kGallerySchemaVersion) return;
  if (empty && !options_.create) throw InputError(path_ + ": empty file, not a bodyrec gallery");
  if (options_.read_only)
    throw InputError(path_ + ": gallery schema version " + std::to_string(version) + " needs an upgrade to " +
                     std::to_string(kGallerySchemaVersion) + "; open it once for writing");
  sql::Transaction upgrade(*db_);
  // Another process may have upgraded it while this one waited for the write lock.
  version = static_cast<int>(db_->query_int("PRAGMA user_version"));
  if (version < kGallerySchemaVersion) store::upgrade_schema(*db_, version);
  upgrade.commit();
}

void Gallery::load_cache() {
  for (auto& view : cache_) view.clear();
  sql::Statement s(*db_,
                   "SELECT user, view, features, descriptor, descriptor_version, quality FROM scans "
                   "ORDER BY user, view");
  while (s.step()) {
    GalleryEntry e;
    e.user = s.column_int(0);
    e.view = static_cast<View>(s.column_int(1));
    e.features = store::decode_features(s.column_blob_data(2), static_cast<size_t>(s.column_bytes(2)),
                                        path_ + ": user " + std::to_string(e.user));
    e.descriptor = s.column_text(3);
    e.descriptor_version = static_cast<int>(s.column_int(4));
    e.quality = s.column_double(5);
    cache_[static_cast<int>(e.view)].push_back(std::move(e));
  }
  data_version_ = db_->query_int("PRAGMA data_version");
  cache_dirty_ = false;
}

bool Gallery::refresh() {
  const int64_t version = db_->query_int("PRAGMA data_version");
  if (version == data_version_ && !cache_dirty_) return false;
  load_cache();
  return true;
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

void Gallery::begin() {
  if (options_.read_only) throw ProcessingError(path_ + ": gallery opened read-only, cannot write");
  if (depth_++ == 0) {
    aborted_ = false;
    try {
      db_->exec("BEGIN IMMEDIATE");
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
    db_->exec("COMMIT");
  } catch (...) {
    rollback_now();
    throw;
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
  sqlite3_exec(db_->handle(), "ROLLBACK", nullptr, nullptr, nullptr);
  // The cache took the rolled-back writes; reload it from the file.
  load_cache();
}

}  // namespace bodyrec
