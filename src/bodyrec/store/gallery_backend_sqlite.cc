// The gallery in an SQLite file: created private (0600), WAL journal, synchronous FULL or NORMAL, a busy
// timeout between processes, secure_delete, and VACUUM + a truncating WAL checkpoint after erasure.
#include <fcntl.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "bodyrec/core/error.h"
#include "bodyrec/store/gallery_backend.h"
#include "bodyrec/store/schema.h"
#include "bodyrec/store/sqlite.h"

namespace bodyrec::store {

namespace {

// Creates an empty file readable and writable by its owner only. The umask can only remove bits from
// open()'s mode, so fchmod sets 0600 exactly. An empty file is a valid empty SQLite database; EEXIST
// (another process created it first) is fine.
void create_private_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    if (errno == EEXIST) return;
    throw ProcessingError(path + ": cannot create gallery: " + std::strerror(errno));  // an output: exit 4
  }
  const int rc = ::fchmod(fd, 0600);
  const int saved = errno;
  ::close(fd);
  if (rc != 0) throw ProcessingError(path + ": cannot set mode 0600: " + std::strerror(saved));
}

class SqliteBackend : public GalleryBackend {
 public:
  SqliteBackend(const std::string& path, const GalleryOptions& options) {
    std::error_code ec;
    const bool exists = std::filesystem::exists(path, ec);
    if (!exists) {
      if (!options.create) throw InputError(path + ": gallery not found");
      create_private_file(path);
    } else if (std::filesystem::is_directory(path, ec)) {
      throw InputError(path + ": is a directory, not a gallery file");
    }
    // A read-only gallery is still opened read-write when the file allows it, with query_only set: only a
    // writable connection can checkpoint and remove the -wal/-shm files when it closes.
    const bool writable = ::access(path.c_str(), W_OK) == 0;
    db_ = std::make_unique<sql::SqliteConnection>(
        path, options.read_only && !writable ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE);
    if (options.read_only) db_->exec("PRAGMA query_only = ON");
    sqlite3_busy_timeout(db_->handle(), options.busy_timeout_ms);
    // The first read of the header: a file that is not SQLite fails here with SQLITE_NOTADB (InputError).
    db_->query_int("PRAGMA user_version");
    db_->exec("PRAGMA foreign_keys = ON");
    // Deleted rows (forget, purge, replaced scans) are overwritten with zeros, not just unlinked.
    db_->exec("PRAGMA secure_delete = ON");
    if (options.read_only) return;
    db_->exec("PRAGMA journal_mode = WAL");
    db_->exec(options.sync_full ? "PRAGMA synchronous = FULL" : "PRAGMA synchronous = NORMAL");
  }

  sql::Connection& connection() override { return *db_; }
  const char* database_kind() const override { return "an SQLite database"; }
  const char* empty_kind() const override { return "empty file"; }

  Stamp stamp() override {
    Stamp s;
    s.version = static_cast<int>(db_->query_int("PRAGMA user_version"));
    const int64_t app = db_->query_int("PRAGMA application_id");
    s.empty = s.version == 0 && app == 0 && db_->query_int("SELECT count(*) FROM sqlite_master") == 0;
    s.ours = app == kGalleryApplicationId;
    return s;
  }
  void begin_upgrade() override { db_->exec("BEGIN IMMEDIATE"); }
  void set_version(int version) override {
    db_->exec("PRAGMA application_id = " + std::to_string(kGalleryApplicationId) +
              "; PRAGMA user_version = " + std::to_string(version));
  }

  // BEGIN IMMEDIATE takes the write lock at once, so two writers queue on the busy timeout instead of
  // deadlocking on a lock upgrade.
  void begin_write() override { db_->exec("BEGIN IMMEDIATE"); }
  bool may_have_changed() override {
    const int64_t version = db_->query_int("PRAGMA data_version");
    const bool changed = version != data_version_;
    data_version_ = version;
    return changed;
  }

  // Deleted rows are already zeroed by secure_delete, but their old pages may still sit in the WAL and
  // the file keeps its size: VACUUM rewrites the database compactly, then a TRUNCATE checkpoint copies
  // the WAL into the file and empties the WAL. A reader in another process can keep the checkpoint from
  // finishing; the report says so (the pages go at the next checkpoint).
  void scrub(EraseReport& report) override {
    db_->exec("VACUUM");
    sql::Statement s(*db_, "PRAGMA wal_checkpoint(TRUNCATE)");
    report.checkpointed = s.step() && s.column_int(0) == 0;
    report.scrubbed = true;
    if (!report.checkpointed)
      report.note = "another process has the gallery open; the erased pages leave the -wal file at its next "
                    "checkpoint";
  }
  std::string integrity_check() override {
    sql::Statement s(*db_, "PRAGMA integrity_check");
    return s.step() ? s.column_text(0) : "";
  }

 private:
  std::unique_ptr<sql::SqliteConnection> db_;
  int64_t data_version_ = -1;
};

}  // namespace

std::unique_ptr<GalleryBackend> make_sqlite_backend(const std::string& path, const GalleryOptions& options) {
  return std::make_unique<SqliteBackend>(path, options);
}

}  // namespace bodyrec::store
