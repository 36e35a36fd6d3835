// Gallery reads for inspection (CLI list/show/export, tests); matching reads the feature cache instead.
#include "bodyrec/core/error.h"
#include "bodyrec/core/parse_number.h"
#include "bodyrec/store/feature_blob.h"
#include "bodyrec/store/gallery.h"
#include "bodyrec/store/connection.h"

namespace bodyrec {

namespace {

constexpr const char* kUserColumns = "SELECT id, label, created_ms, first_seen_ms, last_seen_ms FROM users";

User read_user(const sql::Statement& s) {
  User u;
  u.id = s.column_int(0);
  u.label = s.column_text(1);
  u.created = from_unix_ms(s.column_int(2));
  u.first_seen = from_unix_ms(s.column_int(3));
  u.last_seen = from_unix_ms(s.column_int(4));
  return u;
}

}  // namespace

std::vector<User> Gallery::users() {
  std::vector<User> all;
  {
    sql::Statement s(*db_, std::string(kUserColumns) + " ORDER BY id");
    while (s.step()) all.push_back(read_user(s));
  }
  sql::Statement views(*db_, "SELECT \"user\", view FROM scans ORDER BY \"user\"");
  size_t i = 0;
  while (views.step()) {
    const UserId user = views.column_int(0);
    while (i < all.size() && all[i].id < user) ++i;
    if (i == all.size()) break;
    if (all[i].id != user) continue;
    all[i].views[static_cast<size_t>(views.column_int(1))] = true;
    ++all[i].scans;
  }
  return all;
}

std::optional<User> Gallery::user(UserId id) {
  sql::Statement s(*db_, std::string(kUserColumns) + " WHERE id = ?1");
  s.bind(1, static_cast<int64_t>(id));
  if (!s.step()) return std::nullopt;
  User u = read_user(s);
  sql::Statement views(*db_, "SELECT view FROM scans WHERE \"user\" = ?1");
  views.bind(1, static_cast<int64_t>(id));
  while (views.step()) {
    u.views[static_cast<size_t>(views.column_int(0))] = true;
    ++u.scans;
  }
  return u;
}

int Gallery::user_count() { return static_cast<int>(db_->query_int("SELECT count(*) FROM users")); }

std::vector<UserId> Gallery::users_unseen_since(GalleryTime since) {
  sql::Statement s(*db_, "SELECT id FROM users WHERE last_seen_ms < ?1 ORDER BY id");
  s.bind(1, to_unix_ms(since));
  std::vector<UserId> ids;
  while (s.step()) ids.push_back(s.column_int(0));
  return ids;
}

std::vector<EventSpoolRecord> Gallery::event_spools() {
  sql::Statement s(*db_,
                   "SELECT machine, host, path, sensor, first_used_ms, last_used_ms FROM event_spools "
                   "ORDER BY host, machine, path");
  std::vector<EventSpoolRecord> spools;
  while (s.step()) {
    EventSpoolRecord r;
    r.machine = s.column_text(0);
    r.host = s.column_text(1);
    r.path = s.column_text(2);
    r.sensor = s.column_text(3);
    r.first_used = from_unix_ms(s.column_int(4));
    r.last_used = from_unix_ms(s.column_int(5));
    spools.push_back(std::move(r));
  }
  return spools;
}

int64_t Gallery::scan_count() { return db_->query_int("SELECT count(*) FROM scans"); }

int64_t Gallery::scans_with_images() {
  return db_->query_int("SELECT count(*) FROM scans WHERE image_png IS NOT NULL AND length(image_png) > 0");
}

UserId Gallery::resolve_user(const std::string& id_or_label) {
  if (const auto id = parse_integer(id_or_label)) {
    if (user(*id)) return *id;
    throw InputError(path_ + ": no user " + id_or_label);
  }
  sql::Statement s(*db_, "SELECT id FROM users WHERE label = ?1 AND label != '' ORDER BY id");
  s.bind(1, id_or_label);
  std::vector<UserId> ids;
  while (s.step()) ids.push_back(s.column_int(0));
  if (ids.empty()) throw InputError(path_ + ": no user with id or label '" + id_or_label + "'");
  if (ids.size() > 1)
    throw InputError(path_ + ": label '" + id_or_label + "' names " + std::to_string(ids.size()) +
                     " users; give the id");
  return ids.front();
}

std::vector<StoredScan> Gallery::user_scans(UserId user) {
  sql::Statement s(*db_,
                   "SELECT view, image_png, mask_png, features, descriptor, descriptor_version, quality, time_ms, "
                   "stored_ms FROM scans WHERE \"user\" = ?1 ORDER BY view");
  s.bind(1, static_cast<int64_t>(user));
  std::vector<StoredScan> scans;
  while (s.step()) {
    StoredScan scan;
    scan.user = user;
    scan.view = static_cast<View>(s.column_int(0));
    scan.image_png = s.column_blob(1);
    scan.mask_png = s.column_blob(2);
    scan.features = store::decode_features(s.column_blob_data(3), s.column_bytes(3),
                                           path_ + ": user " + std::to_string(user));
    scan.descriptor = s.column_text(4);
    scan.descriptor_version = static_cast<int>(s.column_int(5));
    scan.quality = s.column_double(6);
    scan.time = from_unix_ms(s.column_int(7));
    if (!s.is_null(8)) scan.stored = from_unix_ms(s.column_int(8));
    scans.push_back(std::move(scan));
  }
  return scans;
}

std::vector<Event> Gallery::events(std::optional<UserId> user) {
  std::string sql = "SELECT id, \"user\", kind, score, view, time_ms, track, source, sensor, logged_ms FROM events";
  sql += user ? " WHERE \"user\" = ?1 ORDER BY id" : " ORDER BY id";
  sql::Statement s(*db_, sql);
  if (user) s.bind(1, static_cast<int64_t>(*user));
  std::vector<Event> events;
  while (s.step()) {
    Event e;
    e.id = s.column_int(0);
    if (!s.is_null(1)) e.user = s.column_int(1);
    const std::string kind = s.column_text(2);
    const auto parsed = parse_event_kind(kind);
    if (!parsed) throw InputError(path_ + ": event " + std::to_string(e.id) + ": unknown kind '" + kind + "'");
    e.kind = *parsed;
    if (!s.is_null(3)) e.score = s.column_double(3);
    if (!s.is_null(4)) e.view = static_cast<View>(s.column_int(4));
    e.time = from_unix_ms(s.column_int(5));
    if (!s.is_null(6)) e.track = s.column_int(6);
    e.source = s.column_text(7);
    e.sensor = s.column_text(8);
    if (!s.is_null(9)) e.logged = from_unix_ms(s.column_int(9));
    events.push_back(std::move(e));
  }
  return events;
}

}  // namespace bodyrec
