// The gallery on PostgreSQL (issue 47), on a private server (tests/support/server_fixtures.h, ctest label
// `server`): the suites every database passes, then what only PostgreSQL has: connection URIs and
// passwords, erasure as pg_dump and the table files see it, a server restart during writes, and the
// least-privilege roles of docs/postgresql-roles.sql.
#include <gtest/gtest.h>

#include "bodyrec/store/gallery.h"
#include "bodyrec/store/gallery_backend_test_support.h"
#include "bodyrec/store/gallery_test_support.h"
#include "bodyrec/store/postgres.h"
#include "test_support.h"

namespace bodyrec::store::testing {

BODYREC_INSTANTIATE_GALLERY_SUITES(sql::Dialect::kPostgres);

namespace {

using bodyrec::testing::contains;
using bodyrec::testing::input_error;
using bodyrec::testing::usage_error;

std::string hex(const std::string& bytes) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (unsigned char c : bytes) {
    out += digits[c >> 4];
    out += digits[c & 15];
  }
  return out;
}

std::string database_of(const std::string& uri) {
  const size_t at = uri.find("///") + 3;
  return uri.substr(at, uri.find('?') - at);
}

class GalleryPostgres : public GalleryDbFixture {
 protected:
  GalleryPostgres() : GalleryDbFixture(sql::Dialect::kPostgres) {}
};

TEST_F(GalleryPostgres, PasswordsInTheUriAreRefusedWithoutRepeatingThem) {  for (const std::string uri : {"postgresql://sensor:s3cret@localhost/site", "postgresql:///site?password=s3cret",
                                "postgres://sensor:s3cret@/site?host=/tmp"}) {
    const std::string m = usage_error([&] { Gallery g(uri); });
    EXPECT_TRUE(contains(m, "holds a password")) << m;
    EXPECT_TRUE(contains(m, "PGPASSFILE")) << m;
    EXPECT_FALSE(contains(m, "s3cret")) << m;
  }
  EXPECT_TRUE(contains(usage_error([&] { Gallery g("postgresql:///site?colour=blue"); }),
                       "--gallery: not a valid PostgreSQL connection URI: invalid URI query parameter: \"colour\""));
}

TEST_F(GalleryPostgres, AMissingDatabaseOrServerIsAnInputErrorNamingTheUri) {
  bodyrec::testing::PostgresServer* pg = pg_;
  const std::string missing = pg->uri("no_such_gallery");
  const std::string m = input_error([&] { Gallery g(missing, creating()); });
  EXPECT_TRUE(contains(m, missing + ": cannot connect: ")) << m;
  EXPECT_TRUE(contains(m, "does not exist")) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos);
  const std::string nowhere = "postgresql:///x?host=/nonexistent-socket-dir";
  EXPECT_TRUE(contains(input_error([&] { Gallery g(nowhere); }), nowhere + ": cannot connect: "));
}

// Issue 47 item 3: after `forget`, a pg_dump of the database holds none of the erased scan's PNG or
// feature bytes (bytea is dumped as hex), and neither do the database's files (VACUUM FULL wrote the
// tables anew and truncated the old files). Only the WAL may still hold them (docs/postgresql.md).
TEST_F(GalleryPostgres, ForgetLeavesNoBytesInPgDumpOrInTheTableFiles) {
  bodyrec::testing::PostgresServer* pg = pg_;
  const std::string uri = fresh();
  const std::string db = database_of(uri);
  Gallery g(uri, creating());
  const GalleryScan secret = distinct_scan(31), other = distinct_scan(32);
  const Patterns p = patterns_of(secret), q = patterns_of(other);
  const UserId u = g.enrol(secret);
  g.put_scan(u, [&] {
    GalleryScan back = distinct_scan(33);
    back.view = View::B;
    return back;
  }());
  g.enrol(other);
  std::string dump = pg->dump(db);
  ASSERT_TRUE(contains(dump, hex(p.image)));  // there before: the test can fail
  ASSERT_TRUE(contains(dump, hex(p.features)));
  ASSERT_TRUE(contains(stored_bytes(uri), p.image));
  const EraseReport r = g.forget(u);
  EXPECT_EQ(r.scans, 2);
  EXPECT_TRUE(r.scrubbed) << r.note;
  EXPECT_TRUE(r.checkpointed);
  dump = pg->dump(db);
  EXPECT_FALSE(contains(dump, hex(p.image)));
  EXPECT_FALSE(contains(dump, hex(p.features)));
  EXPECT_FALSE(contains(dump, hex(patterns_of(distinct_scan(33)).image)));
  EXPECT_TRUE(contains(dump, hex(q.image)));  // the other user is intact
  const std::string files = stored_bytes(uri);
  EXPECT_FALSE(contains(files, p.image));
  EXPECT_FALSE(contains(files, p.features));
  EXPECT_TRUE(contains(files, q.image));
}

// A server restart in the middle of a run: the call that meets it fails with a clear message, nothing
// committed is lost, the transaction that was open is not half-stored, and a new connection carries on.
TEST_F(GalleryPostgres, AServerRestartLosesNoCommittedScan) {
  bodyrec::testing::PostgresServer* pg = pg_;
  const std::string uri = fresh();
  Gallery g(uri, creating());
  for (int i = 0; i < 3; ++i) g.enrol(make_scan(View::F, 0.5, 40 + i));
  pg->restart();
  std::string m;
  try {
    g.enrol(make_scan(View::F, 0.5, 43));
  } catch (const ProcessingError& e) {
    m = e.what();
  }
  EXPECT_TRUE(contains(m, uri + ": lost the connection to the PostgreSQL server")) << m;
  EXPECT_EQ(g.scans(View::F).size(), 3u);  // the cache holds what was committed
  {
    Gallery again(uri);
    EXPECT_EQ(again.user_count(), 3);
    // A transaction open when the server goes away stores nothing of itself.
    EXPECT_THROW(again.transaction([&] {
      again.enrol(make_scan(View::F, 0.5, 44));
      pg->restart();
      again.put_scan(4, make_scan(View::B, 0.5, 45));
    }),
                 ProcessingError);
  }
  Gallery after(uri);
  EXPECT_EQ(after.user_count(), 3);
  ASSERT_EQ(after.scans(View::F).size(), 3u);
  EXPECT_EQ(after.scans(View::F)[2].features.at<float>(0, 0), 42.0f);
  EXPECT_EQ(after.enrol(make_scan(View::F, 0.5, 46)), 5);  // the failed enrolment's id is not reused
}

std::string roles_sql(int part) {
  const std::string text = bodyrec::testing::read_text(bodyrec::testing::source_dir() + "/docs/postgresql-roles.sql");
  const size_t split = text.find("-- Part 2");
  return part == 1 ? text.substr(0, split) : text.substr(split);
}

// The GRANTs of docs/postgresql-roles.sql, as written: a sensor can run re-identification and nothing
// more; the admin creates the schema and erases.
TEST_F(GalleryPostgres, RolesFromTheDocsLetASensorEnrolButNotErase) {
  bodyrec::testing::PostgresServer* pg = pg_;
  const std::string db = database_of(pg->create_database("roles"));
  pg->exec(db, roles_sql(1));
  const std::string admin = pg->uri(db, "bodyrec_admin"), sensor = pg->uri(db, "bodyrec_sensor");
  // A sensor cannot create the schema.
  EXPECT_TRUE(contains(bodyrec::testing::thrown_message<ProcessingError>(
                           [&] { Gallery g(sensor, creating()); }, "ProcessingError"),
                       "permission denied"));
  { Gallery init(admin, creating()); }
  {
    // Part 2 runs as the admin, who owns the tables.
    sql::PgConnection as_admin(admin);
    as_admin.exec(roles_sql(2));
  }
  GalleryOptions o = creating();
  o.sensor = "door";
  o.max_events_per_user = 2;
  Gallery s(sensor, o);
  const UserId u = s.enrol(make_scan(View::F, 0.5, 50));
  EXPECT_EQ(s.put_scan(u, make_scan(View::F, 0.9, 51)), PutResult::kReplaced);
  EXPECT_EQ(s.put_scan(u, make_scan(View::B, 0.9, 52)), PutResult::kInserted);
  Event e;
  e.user = u;
  e.kind = EventKind::kRecognised;
  for (int i = 0; i < 3; ++i) s.log_event(e);  // trims the history
  EXPECT_EQ(s.events(u).size(), 2u);
  s.note_event_spool({"m1", "robot", "/var/lib/bodyrec/door.spool", "door", from_unix_ms(1), from_unix_ms(1)});
  s.note_event_spool({"m1", "robot", "/var/lib/bodyrec/door.spool", "door", from_unix_ms(2), from_unix_ms(2)});
  ASSERT_EQ(s.event_spools().size(), 1u);
  EXPECT_EQ(to_unix_ms(s.event_spools()[0].last_used), 2);
  EXPECT_TRUE(s.drop_event_spool("m1", "/var/lib/bodyrec/door.spool"));
  Gallery a(admin);
  a.enrol(make_scan(View::SL, 0.5, 53));
  EXPECT_TRUE(s.refresh());
  EXPECT_EQ(s.scans(View::SL).size(), 1u);
  const std::string denied =
      bodyrec::testing::thrown_message<ProcessingError>([&] { s.forget(u); }, "ProcessingError");
  EXPECT_TRUE(contains(denied, "permission denied")) << denied;
  EXPECT_THROW(s.purge(), ProcessingError);
  EXPECT_EQ(s.user_count(), 2);
  const EraseReport r = a.forget(u);
  EXPECT_TRUE(r.scrubbed) << r.note;
  EXPECT_TRUE(r.checkpointed);
  EXPECT_EQ(a.user_count(), 1);
}

}  // namespace
}  // namespace bodyrec::store::testing
