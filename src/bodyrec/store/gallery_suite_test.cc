// The gallery's behaviour, the same on both databases (instantiated for SQLite in gallery_test.cc, for
// PostgreSQL in gallery_server_test.cc).
#include <gtest/gtest.h>

#include "bodyrec/store/gallery.h"
#include "bodyrec/store/gallery_backend_test_support.h"
#include "bodyrec/store/gallery_test_support.h"
#include "test_support.h"

namespace bodyrec::store::testing {
namespace {

using bodyrec::testing::contains;
using bodyrec::testing::input_error;

TEST_P(GallerySuite, NewerSchemaIsRefusedNamingBothVersions) {
  const std::string path = fresh();
  { Gallery g(path, creating()); }
  set_schema_version(path, 7);
  EXPECT_EQ(input_error([&] { Gallery g(path); }),
            path + ": gallery schema version 7 is newer than this bodyrec reads (up to 4); use a newer bodyrec");
}

TEST_P(GallerySuite, EmptyGalleryNeedsCreateAndIsThenInitialised) {
  const std::string path = fresh();
  if (!postgres()) bodyrec::testing::write_text(path, "");
  EXPECT_EQ(input_error([&] { Gallery g(path); }),
            path + (postgres() ? ": empty database, not a bodyrec gallery" : ": empty file, not a bodyrec gallery"));
  Gallery g(path, creating());
  EXPECT_EQ(g.user_count(), 0);
  EXPECT_EQ(g.add_user("alice"), 1);
  EXPECT_EQ(g.integrity_check(), "ok");
}

TEST_P(GallerySuite, AnotherApplicationsDatabaseIsRefused) {
  const std::string path = fresh();
  raw_sql(path, "CREATE TABLE t(x INTEGER)");
  EXPECT_EQ(input_error([&] { Gallery g(path, creating()); }),
            path + (postgres() ? ": a PostgreSQL database" : ": an SQLite database") + ", but not a bodyrec gallery");
}

// A schema 1 gallery (events without a sensor) is upgraded on open; its events keep an empty sensor.
TEST_P(GallerySuite, SchemaOneIsUpgradedKeepingEveryRow) {
  const std::string path = fresh();
  UserId u = 0;
  {
    Gallery g(path, creating());
    u = g.enrol(make_scan(View::F, 0.5, 1), "alice", 3, "rec1");
  }
  raw_sql(path, "DROP TABLE event_spools; ALTER TABLE events DROP COLUMN logged_ms; "
                "ALTER TABLE scans DROP COLUMN stored_ms; ALTER TABLE events DROP COLUMN sensor; DROP TABLE gallery_state");
  set_schema_version(path, 1);
  GalleryOptions read_only;
  read_only.read_only = true;
  EXPECT_TRUE(contains(input_error([&] { Gallery g(path, read_only); }),
                       "gallery schema version 1 needs an upgrade to 4; open it once for writing"));
  GalleryOptions o;
  o.sensor = "door";
  Gallery g(path, o);
  ASSERT_EQ(g.events(u).size(), 1u);
  EXPECT_EQ(g.events(u)[0].sensor, "");
  EXPECT_EQ(g.events(u)[0].source, "rec1");
  EXPECT_EQ(g.user(u)->label, "alice");
  ASSERT_EQ(g.scans(View::F).size(), 1u);
  Event e;
  e.user = u;
  e.kind = EventKind::kLeft;
  g.log_event(e);
  EXPECT_EQ(g.events(u)[1].sensor, "door");
  EXPECT_TRUE(g.event_spools().empty());
  { Gallery again(path, read_only); }  // now current
}

// reid runs list their event spools; a second run with the same spool moves last_used, not first_used.
// Spools are told apart by machine id, not host name (two sensors may both be called "raspberrypi").
TEST_P(GallerySuite, EventSpoolsAreListedOncePerMachineAndPath) {
  const std::string path = fresh();
  Gallery g(path, creating());
  EventSpoolRecord a{"m1", "robot", "/var/lib/bodyrec/door.spool", "door", from_unix_ms(1000), from_unix_ms(1000)};
  g.note_event_spool(a);
  g.note_event_spool({"m1", "robot", "/tmp/hall.spool", "hall", from_unix_ms(2000), from_unix_ms(2000)});
  g.note_event_spool({"m2", "robot", a.path, "door", from_unix_ms(3000), from_unix_ms(3000)});  // same name, other machine
  a.host = "robot-2";  // renamed
  a.sensor = "door-2";
  a.first_used = a.last_used = from_unix_ms(5000);
  g.note_event_spool(a);
  std::vector<EventSpoolRecord> spools = g.event_spools();
  ASSERT_EQ(spools.size(), 3u);
  EXPECT_EQ(spools[0].machine, "m1");
  EXPECT_EQ(spools[0].path, "/tmp/hall.spool");
  EXPECT_EQ(spools[1].machine, "m2");
  EXPECT_EQ(spools[2].machine, "m1");
  EXPECT_EQ(spools[2].host, "robot-2");
  EXPECT_EQ(spools[2].path, a.path);
  EXPECT_EQ(spools[2].sensor, "door-2");
  EXPECT_EQ(to_unix_ms(spools[2].first_used), 1000);
  EXPECT_EQ(to_unix_ms(spools[2].last_used), 5000);
  EXPECT_TRUE(g.drop_event_spool("m1", "/tmp/hall.spool"));
  EXPECT_FALSE(g.drop_event_spool("m1", "/tmp/hall.spool"));
  EXPECT_EQ(g.event_spools().size(), 2u);
  // Erasing users leaves the list alone: it names files, not people.
  g.enrol(make_scan(View::F, 0.5, 1));
  g.purge();
  EXPECT_EQ(g.event_spools().size(), 2u);
}

TEST_P(GallerySuite, PutScanKeepsTheBestScanPerUserAndView) {
  Gallery g(fresh(), creating());
  const UserId u = g.add_user();
  EXPECT_EQ(g.put_scan(u, make_scan(View::F, 0.5, 1)), PutResult::kInserted);
  EXPECT_EQ(g.put_scan(u, make_scan(View::F, 0.5, 2)), PutResult::kKept);  // equal is not better
  EXPECT_EQ(g.put_scan(u, make_scan(View::F, 0.4, 3)), PutResult::kKept);
  ASSERT_EQ(g.scans(View::F).size(), 1u);
  EXPECT_EQ(g.scans(View::F)[0].features.at<float>(0, 5), 1.0f);
  EXPECT_EQ(g.put_scan(u, make_scan(View::F, 0.7, 4)), PutResult::kReplaced);
  EXPECT_EQ(g.scans(View::F)[0].features.at<float>(0, 5), 4.0f);
  EXPECT_DOUBLE_EQ(g.scans(View::F)[0].quality, 0.7);
  // Another matcher's features are useless to the current one: replaced even at lower quality.
  auto other = make_scan(View::F, 0.1, 5);
  other.descriptor_version = 2;
  EXPECT_EQ(g.put_scan(u, other), PutResult::kReplaced);
  EXPECT_EQ(g.put_scan(u, make_scan(View::SL, 0.3, 6)), PutResult::kInserted);
  ASSERT_NE(g.find(u, View::SL), nullptr);
  EXPECT_DOUBLE_EQ(g.find(u, View::SL)->quality, 0.3);
  EXPECT_EQ(g.find(u, View::B), nullptr);
  EXPECT_EQ(g.find(u + 1, View::SL), nullptr);

  const auto scans = g.user_scans(u);
  ASSERT_EQ(scans.size(), 2u);
  EXPECT_EQ(scans[0].view, View::F);
  EXPECT_EQ(scans[0].descriptor_version, 2);
  EXPECT_EQ(scans[1].view, View::SL);
  EXPECT_DOUBLE_EQ(scans[1].quality, 0.3);
  EXPECT_EQ(scans[1].features.at<float>(0, 63), 6.0f);
  EXPECT_FALSE(scans[1].image_png.empty());
  EXPECT_FALSE(scans[1].mask_png.empty());
  const auto user = g.user(u);
  ASSERT_TRUE(user);
  EXPECT_EQ(user->scans, 2);
  EXPECT_TRUE(user->views[static_cast<int>(View::F)]);
  EXPECT_TRUE(user->views[static_cast<int>(View::SL)]);
  EXPECT_FALSE(user->views[static_cast<int>(View::B)]);

  EXPECT_TRUE(contains(input_error([&] { g.put_scan(99, make_scan(View::F, 1, 1)); }), "no user 99"));
  auto bad = make_scan(View::F, 1, 1);
  bad.features = cv::Mat();
  EXPECT_THROW(g.put_scan(u, bad), ProcessingError);
}

TEST_P(GallerySuite, CacheIsLoadedOnOpenAndRefreshSeesOtherConnections) {
  const std::string path = fresh();
  {
    Gallery g(path, creating());
    for (int i = 0; i < 3; ++i) g.enrol(make_scan(View::B, 0.5, 10 + i));
  }
  Gallery a(path), b(path);
  ASSERT_EQ(a.scans(View::B).size(), 3u);
  EXPECT_EQ(a.scans(View::B)[2].features.at<float>(0, 0), 12.0f);
  EXPECT_TRUE(a.scans(View::F).empty());
  EXPECT_FALSE(a.refresh());  // nothing changed
  b.enrol(make_scan(View::F, 0.5, 20));
  EXPECT_TRUE(a.scans(View::F).empty());  // not before refresh
  EXPECT_TRUE(a.refresh());
  ASSERT_EQ(a.scans(View::F).size(), 1u);
  EXPECT_EQ(a.scans(View::F)[0].user, 4);
  // One's own writes need no reload, nor do another's events; another's new view and erasure do.
  a.enrol(make_scan(View::SL, 0.5, 21));
  EXPECT_FALSE(a.refresh());
  Event e;
  e.user = 2;
  e.kind = EventKind::kRecognised;
  b.log_event(e);
  b.set_label(2, "bob");
  EXPECT_FALSE(a.refresh());
  b.put_scan(2, make_scan(View::FR, 0.5, 22));
  EXPECT_TRUE(a.refresh());
  EXPECT_NE(a.find(2, View::FR), nullptr);
  // Both wrote scans since a's last refresh: a's own write cannot tell, the next refresh loads b's.
  b.put_scan(3, make_scan(View::FR, 0.5, 23));
  a.put_scan(2, make_scan(View::BL, 0.5, 24));
  EXPECT_TRUE(a.refresh());
  EXPECT_NE(a.find(3, View::FR), nullptr);
  EXPECT_NE(a.find(2, View::BL), nullptr);
  EXPECT_FALSE(a.refresh());
  b.forget(1);
  EXPECT_TRUE(a.refresh());
  EXPECT_EQ(a.scans(View::B).size(), 2u);
  EXPECT_EQ(a.find(1, View::B), nullptr);
}

TEST_P(GallerySuite, NoImagesKeepsFeaturesOnly) {
  GalleryOptions o = creating();
  o.store_images = false;
  Gallery g(fresh(), o);
  const UserId u = g.enrol(make_scan(View::FR, 0.5, 1));
  const auto scans = g.user_scans(u);
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_TRUE(scans[0].image_png.empty());
  EXPECT_TRUE(scans[0].mask_png.empty());
  EXPECT_EQ(scans[0].features.cols, 64);
  EXPECT_EQ(g.scan_count(), 1);
  EXPECT_EQ(g.scans_with_images(), 0);
  // A connection that would store images, told to keep features only, stores none.
  Gallery images(g.path(), creating());
  images.put_scan(u, make_scan(View::B, 0.5, 2));
  EXPECT_EQ(images.scans_with_images(), 1);
  images.keep_features_only();
  images.put_scan(u, make_scan(View::SL, 0.5, 3));
  EXPECT_EQ(images.scan_count(), 3);
  EXPECT_EQ(images.scans_with_images(), 1);
}

TEST_P(GallerySuite, EnrolLogsEventsAndMovesLastSeen) {
  Gallery g(fresh(), creating());
  auto scan = make_scan(View::SR, 0.5, 1);
  scan.time = from_unix_ms(1000000);
  const UserId u = g.enrol(scan, "alice", 3, "rec1");
  Event seen;
  seen.user = u;
  seen.kind = EventKind::kRecognised;
  seen.score = 42.5;
  seen.view = View::SR;
  seen.time = from_unix_ms(5000000);
  seen.track = 8;
  g.log_event(seen);
  const auto events = g.events(u);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, EventKind::kEnrolled);
  EXPECT_EQ(events[0].track, 3);
  EXPECT_EQ(events[0].source, "rec1");
  EXPECT_EQ(events[1].kind, EventKind::kRecognised);
  EXPECT_EQ(events[1].score, 42.5);
  EXPECT_EQ(events[1].view, View::SR);
  EXPECT_EQ(events[1].track, 8);
  EXPECT_EQ(to_unix_ms(events[1].time), 5000000);
  const auto user = g.user(u);
  EXPECT_EQ(user->label, "alice");
  EXPECT_EQ(to_unix_ms(user->first_seen), 1000000);
  EXPECT_EQ(to_unix_ms(user->last_seen), 5000000);
  seen.time = from_unix_ms(2000000);  // an older event moves nothing
  g.log_event(seen);
  EXPECT_EQ(to_unix_ms(g.user(u)->last_seen), 5000000);
  EXPECT_EQ(g.resolve_user("alice"), u);
  EXPECT_EQ(g.resolve_user("1"), u);
  EXPECT_TRUE(contains(input_error([&] { g.resolve_user("bob"); }), "no user with id or label 'bob'"));
  g.set_label(u, "alicia");
  EXPECT_EQ(g.resolve_user("alicia"), u);
  EXPECT_TRUE(contains(input_error([&] { g.set_label(9, "x"); }), "no user 9"));
  seen.user = 77;
  EXPECT_TRUE(contains(input_error([&] { g.log_event(seen); }), "unknown user 77"));
}

// A user who comes back every day must not grow the gallery without bound: only the newest events stay.
TEST_P(GallerySuite, EventHistoryKeepsTheNewestEventsPerUser) {
  GalleryOptions o = creating();
  o.max_events_per_user = 5;
  Gallery g(fresh(), o);
  const UserId a = g.enrol(make_scan(View::F, 0.5, 1)), b = g.enrol(make_scan(View::B, 0.5, 2));
  Event seen;
  seen.kind = EventKind::kRecognised;
  for (int i = 0; i < 20; ++i) {
    seen.user = a;
    seen.score = i;
    seen.time = from_unix_ms(1000 + i);
    g.log_event(seen);
  }
  const auto kept = g.events(a);
  ASSERT_EQ(kept.size(), 5u);
  for (size_t i = 0; i < kept.size(); ++i) EXPECT_EQ(kept[i].score, 15.0 + static_cast<double>(i));  // the newest
  ASSERT_EQ(g.events(b).size(), 1u);  // another user's history is untouched
  EXPECT_EQ(g.events(b)[0].kind, EventKind::kEnrolled);
  // Records without a user (one per forget) are capped the same way.
  for (int i = 0; i < 7; ++i) g.forget(g.enrol(make_scan(View::F, 0.5, 10 + i)));
  int unowned = 0;
  for (const auto& e : g.events())
    if (!e.user) ++unowned;
  EXPECT_EQ(unowned, 5);
  o.max_events_per_user = -1;
  EXPECT_TRUE(contains(bodyrec::testing::usage_error([&] { Gallery(fresh(), o); }),
                       "GalleryOptions.max_events_per_user must be >= 0"));
}

TEST_P(GallerySuite, EventHistoryIsUnlimitedWithZero) {
  GalleryOptions o = creating();
  o.max_events_per_user = 0;
  Gallery g(fresh(), o);
  const UserId a = g.enrol(make_scan(View::F, 0.5, 1));
  Event seen;
  seen.user = a;
  seen.kind = EventKind::kLeft;
  for (int i = 0; i < 1200; ++i) g.log_event(seen);
  EXPECT_EQ(g.events(a).size(), 1201u);
}

TEST_P(GallerySuite, ForgetErasesEverythingOfOneUserAndIdsAreNotReused) {
  Gallery g(fresh(), creating());
  const UserId a = g.enrol(make_scan(View::F, 0.5, 1));
  g.put_scan(a, make_scan(View::B, 0.5, 2));
  Event e;
  e.user = a;
  e.kind = EventKind::kLeft;
  g.log_event(e);
  const UserId b = g.enrol(make_scan(View::F, 0.5, 3));
  const EraseReport r = g.forget(a);
  EXPECT_EQ(r.users, std::vector<UserId>({a}));
  EXPECT_EQ(r.scans, 2);
  EXPECT_EQ(r.images, 2);
  EXPECT_EQ(r.masks, 2);
  EXPECT_EQ(r.events, 2);  // enrolled + left
  EXPECT_TRUE(r.checkpointed);
  EXPECT_TRUE(r.scrubbed);
  EXPECT_EQ(r.note, "");
  EXPECT_FALSE(g.user(a));
  EXPECT_TRUE(g.user(b));
  ASSERT_EQ(g.scans(View::F).size(), 1u);
  EXPECT_EQ(g.scans(View::F)[0].user, b);
  EXPECT_TRUE(g.scans(View::B).empty());
  EXPECT_TRUE(g.events(a).empty());
  // The erasure itself is recorded, without naming anyone.
  const auto all = g.events();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].kind, EventKind::kForgotten);
  EXPECT_FALSE(all[1].user);
  EXPECT_EQ(g.add_user(), 3);
  EXPECT_TRUE(contains(input_error([&] { g.forget(a); }), "no user 1"));
  EXPECT_EQ(g.integrity_check(), "ok");
}

TEST_P(GallerySuite, PruneDropsUsersUnseenForTheRetentionTime) {
  Gallery g(fresh(), creating());
  const GalleryTime now = from_unix_ms(100LL * 86400 * 1000);
  auto old_scan = make_scan(View::F, 0.5, 1);
  old_scan.time = now - std::chrono::hours(24 * 31);
  auto fresh_scan = make_scan(View::F, 0.5, 2);
  fresh_scan.time = now - std::chrono::hours(24 * 29);
  const UserId old_user = g.enrol(old_scan), recent = g.enrol(fresh_scan);
  const EraseReport r = g.prune_unseen(std::chrono::hours(24 * 30), now);
  EXPECT_EQ(r.users, std::vector<UserId>({old_user}));
  EXPECT_EQ(r.scans, 1);
  EXPECT_EQ(r.events, 1);
  EXPECT_FALSE(g.user(old_user));
  EXPECT_TRUE(g.user(recent));
  EXPECT_TRUE(g.prune_unseen(std::chrono::hours(24 * 30), now).users.empty());
}

TEST_P(GallerySuite, PurgeErasesAll) {
  Gallery g(fresh(), creating());
  for (int i = 0; i < 4; ++i) g.enrol(make_scan(View::BL, 0.5, i));
  const EraseReport r = g.purge();
  EXPECT_EQ(r.users.size(), 4u);
  EXPECT_EQ(r.scans, 4);
  EXPECT_EQ(r.events, 4);
  EXPECT_EQ(g.user_count(), 0);
  EXPECT_TRUE(g.events().empty());
  EXPECT_TRUE(g.scans(View::BL).empty());
  EXPECT_EQ(g.add_user(), 5);  // ids are never reused, even after a purge
}

TEST_P(GallerySuite, FailedTransactionWritesNothingAndRestoresTheCache) {
  Gallery g(fresh(), creating());
  EXPECT_THROW(g.transaction([&] {
    g.enrol(make_scan(View::F, 0.5, 1));
    EXPECT_EQ(g.scans(View::F).size(), 1u);
    throw std::runtime_error("camera unplugged");
  }),
               std::runtime_error);
  EXPECT_EQ(g.user_count(), 0);
  EXPECT_TRUE(g.scans(View::F).empty());
  // A failed write inside a transaction rolls the whole of it back.
  EXPECT_THROW(g.transaction([&] {
    g.enrol(make_scan(View::F, 0.5, 1));
    try {
      g.put_scan(42, make_scan(View::B, 0.5, 2));
    } catch (const InputError&) {
    }
  }),
               ProcessingError);
  EXPECT_EQ(g.user_count(), 0);
  g.enrol(make_scan(View::F, 0.5, 3));
  EXPECT_EQ(g.user_count(), 1);
}

TEST_P(GallerySuite, ReadOnlyRefusesWrites) {
  const std::string path = fresh();
  { Gallery(path, creating()).enrol(make_scan(View::F, 0.5, 1)); }
  GalleryOptions o;
  o.read_only = true;
  Gallery g(path, o);
  EXPECT_EQ(g.scans(View::F).size(), 1u);
  EXPECT_THROW(g.add_user(), ProcessingError);
  EXPECT_EQ(g.user_count(), 1);
  o.create = true;
  EXPECT_THROW(o.check(), UsageError);
}

}  // namespace
}  // namespace bodyrec::store::testing
