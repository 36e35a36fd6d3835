// The persistent biometric gallery of re-identification (issue 6, thesis Ch6): users, at most one
// partial scan per (user, view) and an event history, plus an in-memory feature cache so matching a
// probe needs no database round-trip.
//
// Two databases behind one class (issue 47): an SQLite file (the embedded default; `path` is a file
// name) or a PostgreSQL database shared by a site's sensors (`path` is a libpq connection URI,
// postgresql://...; store/postgres.h). The SQL and the logic are the same for both; what differs is in
// store/gallery_backend.h. Everything below holds for both unless it names SQLite.
//
// Crash safety and sharing (issue 7): every write one transaction that keeps other writers out from its
// start (SQLite: BEGIN IMMEDIATE; PostgreSQL: a lock on the gallery's counter row), a busy timeout so
// two processes wait for each other instead of failing. SQLite: WAL journal, synchronous=FULL.
// FULL rather than NORMAL: in WAL mode NORMAL already survives a killed process, but a power cut could
// lose the last commits; gallery writes are rare (per enrolment event, not per frame), so the fsync per
// commit is cheap (bench/gallery_bench.cc) and a robot whose battery dies keeps every reported enrolment.
//
// Privacy: a new file is created mode 0600 whatever the umask (SQLite gives its -wal/-shm the same
// mode); store_images=false keeps features only; forget/purge/prune run with secure_delete, then VACUUM
// and a truncating WAL checkpoint, so erased images and features leave no bytes in the .db or -wal. On
// PostgreSQL they run VACUUM FULL (the tables' owner only) and CHECKPOINT; docs/postgresql.md says what
// stays in the WAL and in backups.
//
// PostgreSQL connection loss (server restart): the call that meets it throws ProcessingError ("lost the
// connection to the PostgreSQL server"); every committed write is kept, the open transaction is not.
// The gallery does not reconnect by itself: a run stops, and a new run carries on from what was
// committed (docs/postgresql.md).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bodyrec/store/gallery_cache.h"
#include "bodyrec/store/gallery_types.h"

namespace bodyrec {

namespace sql {
class Connection;
}

struct GalleryOptions {
  // SQLite: create the file when missing (else InputError naming it). Both: create the schema in an
  // empty database (PostgreSQL: the database itself must exist).
  bool create = false;
  bool read_only = false;    // no writes; the file must exist and have the current schema
  bool store_images = true;  // false: put_scan drops image and mask, keeps features (--no-images)
  int busy_timeout_ms = 10000;  // how long a write waits for another process's transaction
  // synchronous=FULL (fsync per commit: survives power loss). false: NORMAL (survives a killed process,
  // a power cut may lose the last commits); measured in bench/gallery_bench.cc.
  bool sync_full = true;
  // The event history keeps the newest this many events per user (and of the records without a user,
  // `forgotten`/`pruned`); older ones are erased as new ones come, so a file's size is bounded by its
  // users and views however often they come back. 0 keeps every event.
  int max_events_per_user = 1000;
  // Recorded with every event this object logs whose Event::sensor is empty (reid --sensor-id).
  std::string sensor;
  void check() const;  // UsageError for create together with read_only, a negative timeout or event cap
};

// The schema version this build writes (SQLite: PRAGMA user_version; PostgreSQL: bodyrec_gallery).
// Older galleries are migrated on open. 2: events record their sensor. 3: events and scans record the
// wall time at which the gallery wrote them (Event::logged, StoredScan::stored). 4: the event spools of reid
// runs (EventSpoolRecord).
constexpr int kGallerySchemaVersion = 4;

namespace store {
class GalleryBackend;
}

// One Gallery object per thread (it owns one database connection); several processes may share a
// gallery.
class Gallery : public GalleryCache {
 public:
  // Opens (or creates) the gallery at `path` (a file, or a postgresql:// URI) and loads the feature cache.
  // Throws InputError naming the file when it is missing (without create), not an SQLite database,
  // another application's database, or from a newer schema ("... schema version N is newer than this
  // bodyrec reads (up to 4)"); for a URI, also when the server cannot be reached or the database does
  // not exist; UsageError for a URI that holds a password. Older schemas are upgraded in one transaction
  // (not in read_only mode: InputError).
  Gallery(const std::string& path, const GalleryOptions& options = {});
  ~Gallery() override;
  Gallery(const Gallery&) = delete;
  Gallery& operator=(const Gallery&) = delete;

  const std::string& path() const { return path_; }
  const GalleryOptions& options() const { return options_; }

  // ---- writes: each one transaction (or part of the caller's transaction(), see below) ----
  // A new user seen first at `time`; returns its id. Ids are never reused, even after forget.
  UserId add_user(const std::string& label = "", GalleryTime time = GalleryClock::now());
  // Keeps the best scan per (user, view). ENSURES: inserted when the view had none; replaced when
  // scan.quality is strictly higher than the stored one's, or the stored one has another descriptor
  // name/version (its features are useless to the current matcher); otherwise kept unchanged. Also
  // moves the user's last_seen forward to scan.time. An inserted or replaced scan records the wall clock
  // now as its StoredScan::stored. REQUIRES: the user exists (else InputError), scan.features non-empty
  // and quality finite (else ProcessingError).
  PutResult put_scan(UserId user, const GalleryScan& scan);
  // Appends an event (id assigned, returned; Event::logged = the wall clock now, event.logged is
  // ignored); moves the user's last_seen forward to event.time; erases that user's oldest events beyond
  // options().max_events_per_user.
  int64_t log_event(const Event& event);
  // add_user + put_scan + an `enrolled` event, in one transaction.
  UserId enrol(const GalleryScan& scan, const std::string& label = "", std::optional<int64_t> track = {},
               const std::string& source = "");
  void set_label(UserId user, const std::string& label);
  // Lists a reid run's event spool, or moves a listed one's last_used (and host and sensor) to this run's;
  // first_used is kept. Keyed by (machine, path). It changes no user, scan or event.
  void note_event_spool(const EventSpoolRecord& spool);
  // Takes a spool off the list (the file is gone); false when it was not listed.
  bool drop_event_spool(const std::string& machine, const std::string& path);
  // From now on put_scan keeps features only, as with GalleryOptions::store_images = false.
  void keep_features_only() { options_.store_images = false; }

  // Erases every scan (image, mask, features), event and the user row itself, then scrubs the database
  // (SQLite: secure_delete + VACUUM + WAL checkpoint; PostgreSQL: VACUUM FULL + CHECKPOINT). A `forgotten` event without a user id records that an
  // erasure happened. InputError when the user does not exist.
  EraseReport forget(UserId user);
  // Erases every user, scan and event; same scrubbing.
  EraseReport purge();
  // Retention: forgets every user whose last_seen is before now - unseen_for (users_unseen_since).
  EraseReport prune_unseen(std::chrono::seconds unseen_for, GalleryTime now = GalleryClock::now());

  // Runs `body` as one transaction: the writes inside it commit together or not at all (the pipeline
  // uses it to enrol a user with several views atomically). Nested calls join the outer transaction.
  template <typename F>
  void transaction(F&& body) {
    begin();
    try {
      body();
    } catch (...) {
      rollback();
      throw;
    }
    commit();
  }

  // ---- reads ----
  // The feature cache for one view: every stored scan of that view, features only. Loaded at open,
  // kept in step with this object's writes; no database access. Other processes' writes show after
  // refresh(). The reference stays valid, but its contents change with this object's next write or
  // refresh.
  const std::vector<GalleryEntry>& scans(View view) const override { return cache_[static_cast<int>(view)]; }
  // The cached scan of one user and view, or nullptr (no database access). The pipeline checks a
  // candidate's quality against it before calling put_scan, which costs a commit (and an fsync) even
  // when it keeps the stored scan.
  const GalleryEntry* find(UserId user, View view) const override;
  // Reloads the cache when another connection changed scans (gallery_state.scan_changes; SQLite asks
  // only after PRAGMA data_version moved, no I/O when nothing changed; PostgreSQL: one query). Others'
  // events do not reload it. Returns true when it reloaded. Call it once per frame or per decision.
  // Inside transaction() it takes in every commit of others, and none can follow until the transaction
  // ends (the write lock is held from its start): what is decided there is decided against the whole
  // gallery (reid/reid_store.h exclusive).
  bool refresh();

  std::optional<User> user(UserId id);
  std::vector<User> users();  // by id
  // Accepts a numeric id or an exact label (unique); InputError naming the gallery otherwise.
  UserId resolve_user(const std::string& id_or_label);
  std::vector<StoredScan> user_scans(UserId user);  // with pixels, in view order
  std::vector<Event> events(std::optional<UserId> user = {});  // oldest first; all when no user
  int user_count();
  std::vector<UserId> users_unseen_since(GalleryTime since);  // last_seen before `since`, by id
  std::vector<EventSpoolRecord> event_spools();  // by host, machine, then path
  int64_t scan_count();         // stored scans
  int64_t scans_with_images();  // stored scans that hold body pixels (an image)

  // SQLite: PRAGMA integrity_check's first line ("ok" when healthy); PostgreSQL: "ok" when the gallery
  // answers (the server checks its own pages).
  std::string integrity_check();

 private:
  void migrate();
  void load_cache();
  void begin();
  void commit();
  void rollback();
  void rollback_now();
  void scrub(EraseReport& report);
  void erase_user(UserId user, EraseReport& report);
  void touch(UserId user, GalleryTime time);
  void cache_put(const GalleryEntry& entry);
  void cache_erase(UserId user);
  void scans_changed();  // inside a write: counts a change of scans (once per transaction)
  int64_t read_scan_changes();

  std::string path_;
  GalleryOptions options_;
  std::unique_ptr<store::GalleryBackend> backend_;
  sql::Connection* db_ = nullptr;  // backend_'s
  std::array<std::vector<GalleryEntry>, kViewCount> cache_;
  int64_t scan_changes_ = 0;      // gallery_state.scan_changes the cache reflects
  // This transaction's value of scan_changes once it changed scans; whether the cache was current before.
  std::optional<int64_t> txn_scan_changes_;
  bool txn_cache_was_current_ = false;
  int depth_ = 0;                 // nesting of transaction()/internal writes
  bool cache_dirty_ = false;
  bool aborted_ = false;          // an inner write failed: the outer transaction must roll back
};

// Helpers shared by the gallery and its users (CLI, tests).
int64_t to_unix_ms(GalleryTime time);
GalleryTime from_unix_ms(int64_t ms);
// "2026-11-23T13:05:00Z"
std::string format_utc(GalleryTime time);
// "30d", "12h", "45m", "90s", "2w" -> seconds; InputError-free: nullopt for anything else.
std::optional<std::chrono::seconds> parse_duration(const std::string& text);

}  // namespace bodyrec
