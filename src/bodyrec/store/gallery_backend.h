// What the gallery's two databases do differently beyond SQL (store/connection.h): opening a gallery,
// where the schema version lives, how a write transaction keeps other writers out, how a connection
// learns that another one wrote, and how erased rows are scrubbed. The gallery (gallery*.cc) holds all
// the SQL and logic and calls these at those points only.
//
//                     SQLite (a file)                         PostgreSQL (a connection URI)
//  schema version     PRAGMA user_version, application_id     table bodyrec_gallery (one row)
//  write transaction  BEGIN IMMEDIATE (busy timeout)          BEGIN + SELECT ... FOR UPDATE of
//                                                             gallery_state's row (lock_timeout = busy
//                                                             timeout)
//  others' writes     PRAGMA data_version (no I/O), then      gallery_state.scan_changes (one query)
//                     gallery_state.scan_changes
//  after an erasure   secure_delete, VACUUM, WAL checkpoint   VACUUM FULL of the three tables (owner
//                                                             only), CHECKPOINT (when allowed)
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "bodyrec/store/connection.h"
#include "bodyrec/store/gallery.h"

namespace bodyrec::store {

class GalleryBackend {
 public:
  virtual ~GalleryBackend() = default;
  virtual sql::Connection& connection() = 0;

  // For messages: "an SQLite database" / "a PostgreSQL database"; "empty file" / "empty database".
  virtual const char* database_kind() const = 0;
  virtual const char* empty_kind() const = 0;

  struct Stamp {
    int version = 0;     // schema version, 0 when none
    bool ours = false;   // marked as a bodyrec gallery
    bool empty = false;  // holds nothing at all (a new gallery)
  };
  virtual Stamp stamp() = 0;
  // Starts the transaction that creates or upgrades the schema, exclusive against other processes doing
  // the same; stamp() inside it sees what they committed.
  virtual void begin_upgrade() = 0;
  // Inside the upgrade transaction: marks the database as a gallery of schema `version`.
  virtual void set_version(int version) = 0;

  // Starts a write transaction that excludes other writers until it ends (they wait up to the busy
  // timeout).
  virtual void begin_write() = 0;
  void commit() { connection().exec("COMMIT"); }
  // False only when no other connection can have committed anything since the previous call (SQLite's
  // data_version, no I/O); PostgreSQL cannot tell without a query and says true. The gallery then reads
  // gallery_state.scan_changes.
  virtual bool may_have_changed() = 0;

  // After forget/purge/prune, outside any transaction: rewrites the database so that erased rows leave
  // no bytes in its files; says in report.note what it could not do.
  virtual void scrub(EraseReport& report) = 0;
  virtual std::string integrity_check() = 0;
};

std::unique_ptr<GalleryBackend> make_sqlite_backend(const std::string& path, const GalleryOptions& options);
std::unique_ptr<GalleryBackend> make_postgres_backend(const std::string& uri, const GalleryOptions& options);

}  // namespace bodyrec::store
