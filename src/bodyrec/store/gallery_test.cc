#include "bodyrec/store/gallery.h"

#include <sqlite3.h>
#include <sys/stat.h>

#include <gtest/gtest.h>

#include "bodyrec/store/feature_blob.h"
#include "bodyrec/store/gallery_test_support.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using bodyrec::testing::contains;
using bodyrec::testing::input_error;
using bodyrec::testing::TempDir;
using store::testing::make_scan;

GalleryOptions creating() {
  GalleryOptions o;
  o.create = true;
  return o;
}

// Raw SQL on a file, bypassing the gallery (to fake other applications and newer versions).
void raw_exec(const std::string& path, const char* sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, sql, nullptr, nullptr, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
  sqlite3_close(db);
}

int file_mode(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return -1;
  return static_cast<int>(st.st_mode & 0777);
}

TEST(Gallery, NewFileIsSchemaV1AndOwnerOnlyWhateverTheUmask) {
  TempDir dir;
  const std::string path = (dir / "g.db").string();
  const mode_t old = ::umask(0);  // the most permissive umask
  {
    Gallery g(path, creating());
    g.add_user();  // a write creates the -wal and -shm files
    EXPECT_EQ(file_mode(path), 0600);
    EXPECT_EQ(file_mode(path + "-wal"), 0600);
    EXPECT_EQ(file_mode(path + "-shm"), 0600);
    EXPECT_EQ(g.integrity_check(), "ok");
  }
  ::umask(old);
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  sqlite3_stmt* s = nullptr;
  sqlite3_prepare_v2(db, "PRAGMA user_version", -1, &s, nullptr);
  ASSERT_EQ(sqlite3_step(s), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int(s, 0), kGallerySchemaVersion);
  sqlite3_finalize(s);
  sqlite3_prepare_v2(db, "PRAGMA journal_mode", -1, &s, nullptr);
  ASSERT_EQ(sqlite3_step(s), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(s, 0)), "wal");
  sqlite3_finalize(s);
  sqlite3_close(db);
}

TEST(Gallery, BadFilesAreOneLineInputErrorsNamingTheFile) {
  TempDir dir;
  const std::string missing = (dir / "missing.db").string();
  EXPECT_EQ(input_error([&] { Gallery g(missing); }), missing + ": gallery not found");
  EXPECT_FALSE(std::filesystem::exists(missing));  // never created silently

  const std::string text = (dir / "notes.db").string();
  bodyrec::testing::write_text(text, std::string(4096, 'x'));
  const std::string e1 = input_error([&] { Gallery g(text); });
  EXPECT_TRUE(contains(e1, text + ": not an SQLite database")) << e1;

  const std::string empty = (dir / "empty.db").string();
  bodyrec::testing::write_text(empty, "");
  EXPECT_EQ(input_error([&] { Gallery g(empty); }), empty + ": empty file, not a bodyrec gallery");

  const std::string other = (dir / "other.db").string();
  raw_exec(other, "CREATE TABLE t(x)");
  EXPECT_EQ(input_error([&] { Gallery g(other, creating()); }),
            other + ": an SQLite database, but not a bodyrec gallery");

  for (const std::string& m : {e1}) EXPECT_EQ(m.find('\n'), std::string::npos);
}

TEST(Gallery, NewerSchemaIsRefusedNamingBothVersions) {
  TempDir dir;
  const std::string path = (dir / "g.db").string();
  { Gallery g(path, creating()); }
  raw_exec(path, "PRAGMA user_version = 7");
  EXPECT_EQ(input_error([&] { Gallery g(path); }),
            path + ": gallery schema version 7 is newer than this bodyrec reads (up to 1); use a newer bodyrec");
}

TEST(Gallery, EmptyFileWithCreateIsInitialised) {
  TempDir dir;
  const std::string path = (dir / "g.db").string();
  bodyrec::testing::write_text(path, "");
  Gallery g(path, creating());
  EXPECT_EQ(g.user_count(), 0);
  EXPECT_EQ(g.add_user("alice"), 1);
}

TEST(Gallery, PutScanKeepsTheBestScanPerUserAndView) {
  TempDir dir;
  Gallery g((dir / "g.db").string(), creating());
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

TEST(Gallery, CacheIsLoadedOnOpenAndRefreshSeesOtherConnections) {
  TempDir dir;
  const std::string path = (dir / "g.db").string();
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
}

TEST(Gallery, NoImagesKeepsFeaturesOnly) {
  TempDir dir;
  GalleryOptions o = creating();
  o.store_images = false;
  Gallery g((dir / "g.db").string(), o);
  const UserId u = g.enrol(make_scan(View::FR, 0.5, 1));
  const auto scans = g.user_scans(u);
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_TRUE(scans[0].image_png.empty());
  EXPECT_TRUE(scans[0].mask_png.empty());
  EXPECT_EQ(scans[0].features.cols, 64);
}

TEST(Gallery, EnrolLogsEventsAndMovesLastSeen) {
  TempDir dir;
  Gallery g((dir / "g.db").string(), creating());
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
  const auto user = g.user(u);
  EXPECT_EQ(user->label, "alice");
  EXPECT_EQ(to_unix_ms(user->first_seen), 1000000);
  EXPECT_EQ(to_unix_ms(user->last_seen), 5000000);
  EXPECT_EQ(g.resolve_user("alice"), u);
  EXPECT_EQ(g.resolve_user("1"), u);
  EXPECT_TRUE(contains(input_error([&] { g.resolve_user("bob"); }), "no user with id or label 'bob'"));
  seen.user = 77;
  EXPECT_TRUE(contains(input_error([&] { g.log_event(seen); }), "unknown user 77"));
}

// A user who comes back every day must not grow the file without bound: only the newest events stay.
TEST(Gallery, EventHistoryKeepsTheNewestEventsPerUser) {
  TempDir dir;
  GalleryOptions o = creating();
  o.max_events_per_user = 5;
  Gallery g((dir / "g.db").string(), o);
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
  EXPECT_TRUE(contains(testing::usage_error([&] { Gallery((dir / "h.db").string(), o); }), "events kept per user"));
}

TEST(Gallery, EventHistoryIsUnlimitedWithZero) {
  TempDir dir;
  GalleryOptions o = creating();
  o.max_events_per_user = 0;
  Gallery g((dir / "g.db").string(), o);
  const UserId a = g.enrol(make_scan(View::F, 0.5, 1));
  Event seen;
  seen.user = a;
  seen.kind = EventKind::kLeft;
  for (int i = 0; i < 1200; ++i) g.log_event(seen);
  EXPECT_EQ(g.events(a).size(), 1201u);
}

TEST(Gallery, ForgetErasesEverythingOfOneUserAndIdsAreNotReused) {
  TempDir dir;
  Gallery g((dir / "g.db").string(), creating());
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

TEST(Gallery, PruneDropsUsersUnseenForTheRetentionTime) {
  TempDir dir;
  Gallery g((dir / "g.db").string(), creating());
  const GalleryTime now = from_unix_ms(100LL * 86400 * 1000);
  auto old_scan = make_scan(View::F, 0.5, 1);
  old_scan.time = now - std::chrono::hours(24 * 31);
  auto fresh_scan = make_scan(View::F, 0.5, 2);
  fresh_scan.time = now - std::chrono::hours(24 * 29);
  const UserId old_user = g.enrol(old_scan), fresh = g.enrol(fresh_scan);
  const EraseReport r = g.prune_unseen(std::chrono::hours(24 * 30), now);
  EXPECT_EQ(r.users, std::vector<UserId>({old_user}));
  EXPECT_EQ(r.scans, 1);
  EXPECT_EQ(r.events, 1);
  EXPECT_FALSE(g.user(old_user));
  EXPECT_TRUE(g.user(fresh));
  EXPECT_TRUE(g.prune_unseen(std::chrono::hours(24 * 30), now).users.empty());
}

TEST(Gallery, PurgeErasesAll) {
  TempDir dir;
  Gallery g((dir / "g.db").string(), creating());
  for (int i = 0; i < 4; ++i) g.enrol(make_scan(View::BL, 0.5, i));
  const EraseReport r = g.purge();
  EXPECT_EQ(r.users.size(), 4u);
  EXPECT_EQ(r.scans, 4);
  EXPECT_EQ(r.events, 4);
  EXPECT_EQ(g.user_count(), 0);
  EXPECT_TRUE(g.events().empty());
  EXPECT_TRUE(g.scans(View::BL).empty());
}

TEST(Gallery, FailedTransactionWritesNothingAndRestoresTheCache) {
  TempDir dir;
  Gallery g((dir / "g.db").string(), creating());
  EXPECT_THROW(g.transaction([&] {
    g.enrol(make_scan(View::F, 0.5, 1));
    EXPECT_EQ(g.scans(View::F).size(), 1u);
    throw std::runtime_error("camera unplugged");
  }),
               std::runtime_error);
  EXPECT_EQ(g.user_count(), 0);
  EXPECT_TRUE(g.scans(View::F).empty());
}

TEST(Gallery, ReadOnlyRefusesWrites) {
  TempDir dir;
  const std::string path = (dir / "g.db").string();
  { Gallery(path, creating()).enrol(make_scan(View::F, 0.5, 1)); }
  GalleryOptions o;
  o.read_only = true;
  Gallery g(path, o);
  EXPECT_EQ(g.scans(View::F).size(), 1u);
  EXPECT_THROW(g.add_user(), ProcessingError);
  o.create = true;
  EXPECT_THROW(o.check(), UsageError);
}

TEST(FeatureBlob, RoundTripsAnyMatrixAndRejectsCorruptBlobs) {
  cv::Mat kaze(3, 64, CV_32F);
  cv::randu(kaze, -1, 1);
  const cv::Mat back = store::decode_features(store::encode_features(kaze), "x");
  EXPECT_EQ(back.type(), CV_32F);
  EXPECT_EQ(cv::norm(back, kaze, cv::NORM_INF), 0.0);
  const cv::Mat bytes = (cv::Mat_<uint8_t>(1, 3) << 1, 2, 3);
  EXPECT_EQ(store::decode_features(store::encode_features(bytes), "x").at<uint8_t>(0, 2), 3);
  auto blob = store::encode_features(kaze);
  blob.pop_back();
  EXPECT_EQ(input_error([&] { store::decode_features(blob, "g.db: user 1"); }),
            "g.db: user 1: corrupt features blob (767 bytes for 3x64)");
  EXPECT_TRUE(contains(input_error([&] { store::decode_features(std::vector<unsigned char>(5), "g"); }),
                       "no BRF1 header"));
}

TEST(GalleryTime, DurationsAndUtcFormat) {
  EXPECT_EQ(parse_duration("30d"), std::chrono::seconds(30 * 86400));
  EXPECT_EQ(parse_duration("12h"), std::chrono::seconds(12 * 3600));
  EXPECT_EQ(parse_duration("45m"), std::chrono::seconds(45 * 60));
  EXPECT_EQ(parse_duration("2w"), std::chrono::seconds(14 * 86400));
  EXPECT_EQ(parse_duration("0s"), std::chrono::seconds(0));
  for (const char* bad : {"", "d", "30", "30x", "-1d", "1.5d", "d30"}) EXPECT_FALSE(parse_duration(bad)) << bad;
  EXPECT_EQ(format_utc(from_unix_ms(0)), "1970-01-01T00:00:00Z");
  EXPECT_EQ(format_utc(from_unix_ms(1795957200000LL)), "2026-11-29T13:00:00Z");
}

}  // namespace
}  // namespace bodyrec
