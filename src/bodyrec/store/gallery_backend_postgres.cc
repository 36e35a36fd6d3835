// The gallery in a PostgreSQL database (issue 47): several sensors of a site share it. The database must
// exist (the site's administrator creates it); the schema is created in it on first use with create set.
// Passwords never come from the URI (postgres.h): libpq reads PGPASSFILE/~/.pgpass or a service file.
#include <libpq-fe.h>

#include <algorithm>

#include "bodyrec/core/error.h"
#include "bodyrec/store/gallery_backend.h"
#include "bodyrec/store/postgres.h"
#include "bodyrec/store/schema.h"

namespace bodyrec::store {

namespace {

constexpr const char* kApplication = "bodyrec gallery";

class PostgresBackend : public GalleryBackend {
 public:
  PostgresBackend(const std::string& uri, const GalleryOptions& options) {
    db_ = std::make_unique<sql::PgConnection>(uri);
    db_->exec("SET client_min_messages = warning");
    // PostgreSQL's lock_timeout 0 waits for ever; the gallery's busy timeout 0 means "do not wait".
    db_->exec("SET lock_timeout = " + std::to_string(std::max(1, options.busy_timeout_ms)));
    if (options.read_only) db_->exec("SET default_transaction_read_only = on");
    // synchronous_commit off: a server crash may lose the last commits (never corrupts), as SQLite's NORMAL.
    if (!options.sync_full) db_->exec("SET synchronous_commit = off");
  }

  sql::Connection& connection() override { return *db_; }
  const char* database_kind() const override { return "a PostgreSQL database"; }
  const char* empty_kind() const override { return "empty database"; }

  Stamp stamp() override {
    Stamp s;
    if (db_->query_int("SELECT to_regclass('bodyrec_gallery') IS NOT NULL") != 0) {
      sql::Statement st(*db_, "SELECT application, schema_version FROM bodyrec_gallery");
      if (st.step()) {
        s.ours = st.column_text(0) == kApplication;
        s.version = static_cast<int>(st.column_int(1));
      }
      return s;
    }
    s.empty = db_->query_int("SELECT count(*) FROM pg_class c JOIN pg_namespace n ON n.oid = c.relnamespace "
                             "WHERE n.nspname = current_schema() AND c.relkind IN ('r', 'p', 'v', 'm', 'f')") == 0;
    return s;
  }
  // The advisory lock (keyed on the gallery's application id) queues processes creating the schema at
  // once; the first creates it, the others then find it done.
  void begin_upgrade() override {
    db_->exec("BEGIN");
    db_->exec("SELECT pg_advisory_xact_lock(" + std::to_string(kGalleryApplicationId) + ")");
  }
  void set_version(int version) override {
    db_->exec(
        "CREATE TABLE IF NOT EXISTS bodyrec_gallery("
        "  one BOOLEAN PRIMARY KEY DEFAULT TRUE CHECK (one),"
        "  application TEXT NOT NULL,"
        "  schema_version INTEGER NOT NULL)");
    sql::Statement s(*db_,
                     "INSERT INTO bodyrec_gallery(application, schema_version) VALUES (?1, ?2) "
                     "ON CONFLICT (one) DO UPDATE SET schema_version = EXCLUDED.schema_version");
    s.bind(1, std::string(kApplication)).bind(2, static_cast<int64_t>(version)).run();
  }

  // The lock on gallery_state's row is the gallery's write lock: held from the first statement of a write
  // to its commit, so writers take turns as on SQLite (a scan's best-of check and its write see one
  // state; reads do not wait for it).
  void begin_write() override {
    db_->exec("BEGIN");
    try {
      db_->exec("SELECT id FROM gallery_state FOR UPDATE");
    } catch (...) {
      db_->rollback_quietly();
      throw;
    }
  }
  bool may_have_changed() override { return true; }

  // DELETE leaves the rows' bytes in the tables' files until their space is reused; VACUUM FULL writes
  // each table anew and truncates the old files. Only the tables' owner may run it (PostgreSQL skips the
  // table with a warning otherwise). CHECKPOINT then lets the WAL segments that still hold the erased
  // rows be recycled sooner; it needs the pg_checkpoint role. docs/postgresql.md says what remains.
  void scrub(EraseReport& report) override {
    db_->take_warnings();
    try {
      db_->exec("VACUUM (FULL) users, scans, events");
      const auto warnings = db_->take_warnings();
      report.scrubbed = warnings.empty();
      if (!warnings.empty())
        report.note = "not vacuumed (" + warnings.front() +
                      "): the erased rows are deleted but their bytes stay in the tables' files until the "
                      "gallery's owner role runs VACUUM FULL";
    } catch (const ProcessingError& e) {
      report.scrubbed = false;
      report.note = std::string("not vacuumed: ") + e.what();
    }
    try {
      db_->exec("CHECKPOINT");
      report.checkpointed = true;
    } catch (const ProcessingError&) {
      report.checkpointed = false;  // no pg_checkpoint role: the server's next checkpoint does it
    }
  }
  std::string integrity_check() override {
    db_->query_int("SELECT count(*) FROM bodyrec_gallery");
    return "ok";
  }

 private:
  std::unique_ptr<sql::PgConnection> db_;
};

}  // namespace

std::unique_ptr<GalleryBackend> make_postgres_backend(const std::string& uri, const GalleryOptions& options) {
  return std::make_unique<PostgresBackend>(uri, options);
}

}  // namespace bodyrec::store
