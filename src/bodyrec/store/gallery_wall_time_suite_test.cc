// Events and scans keep the wall time at which the gallery wrote them (Event::logged, StoredScan::stored)
// beside the source's time (`time`), on both databases, and a schema 2 gallery (without them) upgrades
// keeping every row, with the wall times absent.
#include <chrono>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bodyrec/store/gallery.h"
#include "bodyrec/store/gallery_backend_test_support.h"
#include "bodyrec/store/gallery_json.h"
#include "bodyrec/store/gallery_test_support.h"
#include "test_support.h"

namespace bodyrec::store::testing {
namespace {

using bodyrec::testing::contains;
using bodyrec::testing::input_error;

// The wall clock, in the milliseconds the gallery keeps.
GalleryTime now_ms() { return from_unix_ms(to_unix_ms(GalleryClock::now())); }

TEST_P(GallerySuite, WallTimesAreWhenTheGalleryWroteNotTheSourcesTime) {
  Gallery g(fresh(), creating());
  const GalleryTime month_ago = now_ms() - std::chrono::hours(24 * 30);
  GalleryScan scan = make_scan(View::F, 0.5, 1);
  scan.time = month_ago;
  const GalleryTime before = now_ms();
  const UserId u = g.enrol(scan, "alice", 3, "rec1");
  Event e;
  e.user = u;
  e.kind = EventKind::kRecognised;
  e.time = month_ago + std::chrono::seconds(2);
  e.logged = from_unix_ms(0);  // the gallery sets it, whatever the caller says
  g.log_event(e);
  const GalleryTime after = GalleryClock::now();

  const auto events = g.events(u);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].time, month_ago);
  EXPECT_EQ(events[1].time, month_ago + std::chrono::seconds(2));
  for (const Event& logged : events) {
    ASSERT_TRUE(logged.logged) << logged.id;
    EXPECT_GE(*logged.logged, before) << logged.id;
    EXPECT_LE(*logged.logged, after) << logged.id;
  }
  auto scans = g.user_scans(u);
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_EQ(scans[0].time, month_ago);
  ASSERT_TRUE(scans[0].stored);
  EXPECT_GE(*scans[0].stored, before);
  EXPECT_LE(*scans[0].stored, after);
  EXPECT_EQ(g.user(u)->last_seen, month_ago + std::chrono::seconds(2));

  // A kept scan keeps its wall time; a replaced one gets the replacement's.
  const GalleryTime first_stored = *scans[0].stored;
  std::this_thread::sleep_for(std::chrono::milliseconds(5));  // the clock moves past first_stored's ms
  const GalleryTime before_replace = now_ms();
  ASSERT_GT(before_replace, first_stored);
  scan.time = month_ago + std::chrono::seconds(5);
  EXPECT_EQ(g.put_scan(u, scan), PutResult::kKept);
  EXPECT_EQ(g.user_scans(u)[0].stored, first_stored);
  scan.quality = 0.75;
  EXPECT_EQ(g.put_scan(u, scan), PutResult::kReplaced);
  scans = g.user_scans(u);
  EXPECT_EQ(scans[0].time, month_ago + std::chrono::seconds(5));
  ASSERT_TRUE(scans[0].stored);
  EXPECT_GE(*scans[0].stored, before_replace);
  EXPECT_LE(*scans[0].stored, GalleryClock::now());

  // JSON (show, export): `time` the source's, `stored`/`logged` the wall clock, same UTC format.
  const nlohmann::json scan_json = scan_to_json(scans[0]);
  EXPECT_EQ(scan_json["time"], format_utc(month_ago + std::chrono::seconds(5)));
  EXPECT_EQ(scan_json["stored"], format_utc(*scans[0].stored));
  const nlohmann::json event_json = event_to_json(events[1]);
  EXPECT_EQ(event_json["time"], format_utc(month_ago + std::chrono::seconds(2)));
  EXPECT_EQ(event_json["logged"], format_utc(*events[1].logged));
}

// A schema 2 gallery (no wall times) is upgraded on open; its rows stay, their wall times absent (not
// 1970); new rows get them.
TEST_P(GallerySuite, SchemaTwoIsUpgradedKeepingEveryRowWithoutWallTimes) {
  const std::string path = fresh();
  UserId u = 0;
  {
    GalleryOptions o = creating();
    o.sensor = "door";
    Gallery g(path, o);
    u = g.enrol(make_scan(View::F, 0.5, 1), "alice", 3, "rec1");
    g.put_scan(u, make_scan(View::SL, 0.5, 2));
    Event e;
    e.user = u;
    e.kind = EventKind::kRecognised;
    e.score = 0.25;
    g.log_event(e);
  }
  // Schema 3's columns and schema 4's table dropped, version 2: the layout and rows of a gallery of version 2.
  raw_sql(path, "DROP TABLE event_spools; ALTER TABLE events DROP COLUMN logged_ms; ALTER TABLE scans DROP COLUMN stored_ms");
  set_schema_version(path, 2);
  GalleryOptions read_only;
  read_only.read_only = true;
  EXPECT_TRUE(contains(input_error([&] { Gallery g(path, read_only); }),
                       "gallery schema version 2 needs an upgrade to 4; open it once for writing"));

  Gallery g(path);
  EXPECT_EQ(g.user(u)->label, "alice");
  auto events = g.events(u);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, EventKind::kEnrolled);
  EXPECT_EQ(events[0].source, "rec1");
  EXPECT_EQ(events[0].sensor, "door");
  EXPECT_EQ(events[1].score, 0.25);
  for (const Event& e : events) EXPECT_FALSE(e.logged) << e.id;
  const auto scans = g.user_scans(u);
  ASSERT_EQ(scans.size(), 2u);
  EXPECT_EQ(scans[1].features.at<float>(0, 0), 2.0f);
  for (const StoredScan& s : scans) EXPECT_FALSE(s.stored) << view_name(s.view);
  EXPECT_EQ(g.scans(View::SL).size(), 1u);
  EXPECT_FALSE(event_to_json(events[0]).contains("logged"));
  EXPECT_FALSE(scan_to_json(scans[0]).contains("stored"));

  const GalleryTime before = now_ms();
  Event e;
  e.user = u;
  e.kind = EventKind::kLeft;
  g.log_event(e);
  EXPECT_EQ(g.put_scan(u, make_scan(View::F, 0.9, 3)), PutResult::kReplaced);
  events = g.events(u);
  ASSERT_EQ(events.size(), 3u);
  ASSERT_TRUE(events[2].logged);
  EXPECT_GE(*events[2].logged, before);
  EXPECT_FALSE(events[0].logged);
  ASSERT_TRUE(g.user_scans(u)[0].stored);
  EXPECT_GE(*g.user_scans(u)[0].stored, before);
  EXPECT_FALSE(g.user_scans(u)[1].stored);
  { Gallery again(path, read_only); }  // now current
}

}  // namespace
}  // namespace bodyrec::store::testing
