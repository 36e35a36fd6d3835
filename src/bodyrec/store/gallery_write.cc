// Gallery writes: every public write is one transaction (or joins the caller's transaction()), and the
// feature cache follows each write so matching never needs to read the file.
#include <cmath>

#include <opencv2/imgcodecs.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/store/feature_blob.h"
#include "bodyrec/store/gallery.h"
#include "bodyrec/store/connection.h"
#include "bodyrec/store/gallery_backend.h"

namespace bodyrec {

namespace {

std::vector<unsigned char> encode_png(const cv::Mat& image, const std::string& what) {
  std::vector<unsigned char> png;
  if (image.empty()) return png;
  if (!cv::imencode(".png", image, png)) throw ProcessingError(what + ": cannot encode PNG");
  return png;
}

int64_t count(sql::Connection& db, const char* sql, UserId user) {
  sql::Statement s(db, sql);
  s.bind(1, static_cast<int64_t>(user));
  return s.step() ? s.column_int(0) : 0;
}

}  // namespace

void Gallery::touch(UserId user, GalleryTime time) {
  sql::Statement s(*db_,
                   "UPDATE users SET last_seen_ms = CASE WHEN last_seen_ms < ?1 THEN ?1 ELSE last_seen_ms END, "
                   "first_seen_ms = CASE WHEN first_seen_ms > ?1 THEN ?1 ELSE first_seen_ms END WHERE id = ?2");
  s.bind(1, to_unix_ms(time)).bind(2, static_cast<int64_t>(user)).run();
}

UserId Gallery::add_user(const std::string& label, GalleryTime time) {
  UserId id = 0;
  transaction([&] {
    sql::Statement s(*db_,
                     "INSERT INTO users(label, created_ms, first_seen_ms, last_seen_ms) VALUES (?1, ?2, ?3, ?3) "
                     "RETURNING id");
    s.bind(1, label).bind(2, to_unix_ms(GalleryClock::now())).bind(3, to_unix_ms(time));
    if (!s.step()) throw ProcessingError(path_ + ": adding a user returned no id");
    id = s.column_int(0);
    s.reset();
  });
  return id;
}

void Gallery::set_label(UserId user, const std::string& label) {
  transaction([&] {
    sql::Statement s(*db_, "UPDATE users SET label = ?1 WHERE id = ?2");
    s.bind(1, label).bind(2, static_cast<int64_t>(user));
    while (s.step()) {
    }
    if (s.changes() == 0) throw InputError(path_ + ": no user " + std::to_string(user));
  });
}

void Gallery::note_event_spool(const EventSpoolRecord& spool) {
  transaction([&] {
    sql::Statement s(*db_,
                     "INSERT INTO event_spools(machine, host, path, sensor, first_used_ms, last_used_ms) "
                     "VALUES (?1, ?2, ?3, ?4, ?5, ?6) ON CONFLICT (machine, path) DO UPDATE SET host = excluded.host, "
                     "sensor = excluded.sensor, last_used_ms = excluded.last_used_ms");
    s.bind(1, spool.machine).bind(2, spool.host).bind(3, spool.path).bind(4, spool.sensor);
    s.bind(5, to_unix_ms(spool.first_used)).bind(6, to_unix_ms(spool.last_used)).run();
  });
}

bool Gallery::drop_event_spool(const std::string& machine, const std::string& path) {
  bool dropped = false;
  transaction([&] {
    sql::Statement s(*db_, "DELETE FROM event_spools WHERE machine = ?1 AND path = ?2");
    s.bind(1, machine).bind(2, path).run();
    dropped = s.changes() > 0;
  });
  return dropped;
}

PutResult Gallery::put_scan(UserId user, const GalleryScan& scan) {
  const std::string what = path_ + ": user " + std::to_string(user) + " view " + view_name(scan.view);
  if (scan.features.empty()) throw ProcessingError(what + ": scan has no features");
  if (!std::isfinite(scan.quality)) throw ProcessingError(what + ": scan quality is not finite");
  // Encode outside the transaction: the write lock is held only for the SQL.
  const auto features = store::encode_features(scan.features);
  std::vector<unsigned char> image, mask;
  if (options_.store_images) {
    image = encode_png(scan.image, what);
    mask = encode_png(scan.mask, what);
  }
  PutResult result = PutResult::kKept;
  transaction([&] {
    if (count(*db_, "SELECT count(*) FROM users WHERE id = ?1", user) == 0)
      throw InputError(path_ + ": no user " + std::to_string(user));
    sql::Statement old(*db_,
                       "SELECT quality, descriptor, descriptor_version FROM scans WHERE \"user\" = ?1 AND view = ?2");
    old.bind(1, static_cast<int64_t>(user)).bind(2, static_cast<int64_t>(scan.view));
    const char* sql = nullptr;
    if (!old.step()) {
      result = PutResult::kInserted;
      sql = "INSERT INTO scans(\"user\", view, image_png, mask_png, features, descriptor, descriptor_version, "
            "quality, time_ms, stored_ms) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10)";
    } else if (scan.quality > old.column_double(0) || old.column_text(1) != scan.descriptor ||
               old.column_int(2) != scan.descriptor_version) {
      result = PutResult::kReplaced;
      sql = "UPDATE scans SET image_png = ?3, mask_png = ?4, features = ?5, descriptor = ?6, "
            "descriptor_version = ?7, quality = ?8, time_ms = ?9, stored_ms = ?10 WHERE \"user\" = ?1 AND view = ?2";
    }
    old.reset();
    if (sql) {
      sql::Statement s(*db_, sql);
      s.bind(1, static_cast<int64_t>(user)).bind(2, static_cast<int64_t>(scan.view));
      s.bind_blob(3, image).bind_blob(4, mask).bind_blob(5, features);
      s.bind(6, scan.descriptor).bind(7, static_cast<int64_t>(scan.descriptor_version));
      s.bind(8, scan.quality).bind(9, to_unix_ms(scan.time)).bind(10, to_unix_ms(GalleryClock::now())).run();
    }
    touch(user, scan.time);
    if (sql) {
      scans_changed();
      GalleryEntry entry;
      entry.user = user;
      entry.view = scan.view;
      entry.features = scan.features.clone();
      entry.descriptor = scan.descriptor;
      entry.descriptor_version = scan.descriptor_version;
      entry.quality = scan.quality;
      cache_put(entry);
    }
  });
  return result;
}

int64_t Gallery::log_event(const Event& event) {
  int64_t id = 0;
  transaction([&] {
    if (event.user && count(*db_, "SELECT count(*) FROM users WHERE id = ?1", *event.user) == 0)
      throw InputError(path_ + ": event for unknown user " + std::to_string(*event.user));
    sql::Statement s(*db_,
                     "INSERT INTO events(\"user\", kind, score, view, time_ms, track, source, sensor, logged_ms) "
                     "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9) RETURNING id");
    s.bind(1, event.user ? std::optional<int64_t>(*event.user) : std::nullopt);
    s.bind(2, std::string(event_kind_name(event.kind))).bind(3, event.score);
    s.bind(4, event.view ? std::optional<int64_t>(static_cast<int64_t>(*event.view)) : std::nullopt);
    s.bind(5, to_unix_ms(event.time)).bind(6, event.track).bind(7, event.source);
    s.bind(8, event.sensor.empty() ? options_.sensor : event.sensor).bind(9, to_unix_ms(GalleryClock::now()));
    if (!s.step()) throw ProcessingError(path_ + ": logging an event returned no id");
    id = s.column_int(0);
    s.reset();
    if (event.user) touch(*event.user, event.time);
    if (options_.max_events_per_user > 0) {
      // The newest max_events_per_user of this user's events stay (events_user indexes (user, id); an
      // equality, not IS NOT DISTINCT FROM, so that PostgreSQL uses the index too); SQLite's
      // secure_delete zeroes the erased rows.
      sql::Statement trim(*db_, event.user ? "DELETE FROM events WHERE \"user\" = ?2 AND id <= (SELECT id FROM events "
                                             "WHERE \"user\" = ?2 ORDER BY id DESC LIMIT 1 OFFSET ?1)"
                                           : "DELETE FROM events WHERE \"user\" IS NULL AND id <= (SELECT id FROM "
                                             "events WHERE \"user\" IS NULL ORDER BY id DESC LIMIT 1 OFFSET ?1)");
      if (event.user) trim.bind(2, static_cast<int64_t>(*event.user));
      trim.bind(1, static_cast<int64_t>(options_.max_events_per_user)).run();
    }
  });
  return id;
}

UserId Gallery::enrol(const GalleryScan& scan, const std::string& label, std::optional<int64_t> track,
                      const std::string& source) {
  UserId id = 0;
  transaction([&] {
    id = add_user(label, scan.time);
    put_scan(id, scan);
    Event e;
    e.user = id;
    e.kind = EventKind::kEnrolled;
    e.view = scan.view;
    e.time = scan.time;
    e.track = track;
    e.source = source;
    log_event(e);
  });
  return id;
}

void Gallery::erase_user(UserId user, EraseReport& report) {
  scans_changed();
  report.users.push_back(user);
  report.scans += static_cast<int>(count(*db_, "SELECT count(*) FROM scans WHERE \"user\" = ?1", user));
  report.images += static_cast<int>(
      count(*db_, "SELECT count(*) FROM scans WHERE \"user\" = ?1 AND image_png IS NOT NULL", user));
  report.masks += static_cast<int>(
      count(*db_, "SELECT count(*) FROM scans WHERE \"user\" = ?1 AND mask_png IS NOT NULL", user));
  report.events += static_cast<int>(count(*db_, "SELECT count(*) FROM events WHERE \"user\" = ?1", user));
  for (const char* sql : {"DELETE FROM events WHERE \"user\" = ?1", "DELETE FROM scans WHERE \"user\" = ?1",
                          "DELETE FROM users WHERE id = ?1"}) {
    sql::Statement s(*db_, sql);
    s.bind(1, static_cast<int64_t>(user)).run();
  }
  cache_erase(user);
}

// The backend rewrites the database so that the erased rows leave no bytes in its files (gallery_backend.h).
void Gallery::scrub(EraseReport& report) {
  if (depth_ > 0) throw ProcessingError(path_ + ": forget/purge/prune cannot run inside a transaction");
  backend_->scrub(report);
}

EraseReport Gallery::forget(UserId user) {
  if (depth_ > 0) throw ProcessingError(path_ + ": forget cannot run inside a transaction");
  EraseReport report;
  transaction([&] {
    if (count(*db_, "SELECT count(*) FROM users WHERE id = ?1", user) == 0)
      throw InputError(path_ + ": no user " + std::to_string(user));
    erase_user(user, report);
    Event e;
    e.kind = EventKind::kForgotten;  // records that an erasure happened, not whose
    log_event(e);
  });
  scrub(report);
  return report;
}

EraseReport Gallery::purge() {
  if (depth_ > 0) throw ProcessingError(path_ + ": purge cannot run inside a transaction");
  EraseReport report;
  transaction([&] {
    sql::Statement ids(*db_, "SELECT id FROM users ORDER BY id");
    while (ids.step()) report.users.push_back(ids.column_int(0));
    ids.reset();
    report.scans = static_cast<int>(db_->query_int("SELECT count(*) FROM scans"));
    report.images = static_cast<int>(db_->query_int("SELECT count(*) FROM scans WHERE image_png IS NOT NULL"));
    report.masks = static_cast<int>(db_->query_int("SELECT count(*) FROM scans WHERE mask_png IS NOT NULL"));
    report.events = static_cast<int>(db_->query_int("SELECT count(*) FROM events"));
    scans_changed();
    db_->exec("DELETE FROM events; DELETE FROM scans; DELETE FROM users;");
    for (auto& view : cache_) view.clear();
  });
  scrub(report);
  return report;
}

EraseReport Gallery::prune_unseen(std::chrono::seconds unseen_for, GalleryTime now) {
  if (depth_ > 0) throw ProcessingError(path_ + ": prune cannot run inside a transaction");
  EraseReport report;
  transaction([&] {
    const std::vector<UserId> stale = users_unseen_since(now - unseen_for);
    for (UserId u : stale) erase_user(u, report);
    if (!stale.empty()) {
      Event e;
      e.kind = EventKind::kPruned;
      e.time = now;
      log_event(e);
    }
  });
  if (!report.users.empty()) scrub(report);
  return report;
}

}  // namespace bodyrec
