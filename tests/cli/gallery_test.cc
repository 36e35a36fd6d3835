// `bodyrec gallery` as an operator meets it: list/show/export/forget/purge/prune on a gallery built with
// known users, and the errors for missing, foreign and newer-schema files.
#include <unistd.h>

#include <filesystem>

#include <sqlite3.h>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/store/gallery.h"
#include "bodyrec/store/gallery_test_support.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

using store::testing::make_scan;

const GalleryTime kT0 = from_unix_ms(1795179600000LL);  // 2026-11-20T13:00:00Z, before these tests were written

GalleryScan scan_at(View view, double quality, int seed, int minutes) {
  GalleryScan s = make_scan(view, quality, seed);
  s.time = kT0 + std::chrono::minutes(minutes);
  return s;
}

// User 1 "alice": F, FR, SL, B (enrolled at 13:00, last seen 13:05 recognised); user 2: BL only.
std::string make_gallery(const TempDir& dir) {
  const std::string path = (dir / "g.db").string();
  GalleryOptions o;
  o.create = true;
  Gallery g(path, o);
  const UserId alice = g.enrol(scan_at(View::F, 0.5, 1, 0), "alice", 4, "rec1");
  g.put_scan(alice, scan_at(View::FR, 0.25, 2, 1));
  g.put_scan(alice, scan_at(View::SL, 0.75, 3, 2));
  g.put_scan(alice, scan_at(View::B, 0.125, 4, 3));
  Event e;
  e.user = alice;
  e.kind = EventKind::kRecognised;
  e.score = 24;
  e.view = View::SL;
  e.time = kT0 + std::chrono::minutes(5);
  e.track = 9;
  e.source = "rec2";
  g.log_event(e);
  g.enrol(scan_at(View::BL, 0.5, 5, 10));
  return path;
}

TEST(GalleryCli, ListShowsViewsScansAndTimes) {
  TempDir dir;
  const std::string path = make_gallery(dir);
  const RunResult r = run_bodyrec({"gallery", "--gallery", path, "list", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, path + ": 2 users")) << r.out;
  EXPECT_TRUE(contains(r.out, "1     alice        F  FR .  .  SL B  .  .  4     2026-11-20T13:00:00Z 2026-11-20T13:05:00Z"))
      << r.out;
  EXPECT_TRUE(contains(r.out, "2     -            .  .  .  .  .  .  .  BL 1     2026-11-20T13:10:00Z")) << r.out;
  const auto j = last_json_line(r.out);
  ASSERT_EQ(j["users"].size(), 2u);
  EXPECT_EQ(j["users"][0]["views"], nlohmann::json({"F", "FR", "SL", "B"}));
  EXPECT_EQ(j["users"][0]["scans"], 4);
  EXPECT_EQ(j["users"][0]["last_seen"], "2026-11-20T13:05:00Z");
  EXPECT_EQ(j["users"][1]["label"], "");
  // --gallery also after the subcommand.
  EXPECT_EQ(run_bodyrec({"gallery", "list", "--gallery", path}).exit_code, 0);
}

TEST(GalleryCli, ShowByIdOrLabel) {
  TempDir dir;
  const std::string path = make_gallery(dir);
  const RunResult r = run_bodyrec({"gallery", "--gallery", path, "show", "alice", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "user 1 \"alice\"")) << r.out;
  EXPECT_TRUE(contains(r.out, "4 scans")) << r.out;
  EXPECT_TRUE(contains(r.out, "SL    0.750    yes   yes   test v1 1x64 32F             2026-11-20T13:02:00Z")) << r.out;
  EXPECT_TRUE(contains(r.out, "2026-11-20T13:00:00Z  enrolled  view F  track 4  source rec1")) << r.out;
  EXPECT_TRUE(contains(r.out, "2026-11-20T13:05:00Z  recognised  view SL  score 24.0  track 9  source rec2")) << r.out;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["user"]["id"], 1);
  ASSERT_EQ(j["scans"].size(), 4u);
  EXPECT_EQ(j["scans"][3]["view"], "B");
  EXPECT_EQ(j["scans"][3]["quality"], 0.125);
  ASSERT_EQ(j["events"].size(), 2u);
  EXPECT_EQ(j["events"][1]["score"], 24.0);
  EXPECT_EQ(last_json_line(run_bodyrec({"gallery", "--gallery", path, "show", "2", "--json"}).out)["scans"][0]["view"],
            "BL");
  const RunResult bad = run_bodyrec({"gallery", "--gallery", path, "show", "bob"});
  EXPECT_EQ(bad.exit_code, 3);
  EXPECT_EQ(bad.err, "bodyrec: error: " + path + ": no user with id or label 'bob'\n");
}

// `time` is the source's clock (the footage's 2026-11-20), `stored`/`logged` when bodyrec wrote the row;
// rows of a schema 2 gallery have none ("-" in the text, no key in the JSON).
TEST(GalleryCli, ShowAndExportGiveTheWallTimeBesideTheSourcesTime) {
  TempDir dir;
  const std::string before = format_utc(GalleryClock::now());
  const std::string path = make_gallery(dir);
  RunResult r = run_bodyrec({"gallery", "--gallery", path, "show", "alice", "--json"});
  const std::string after = format_utc(GalleryClock::now());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = last_json_line(r.out);
  ASSERT_EQ(j["scans"].size(), 4u);
  EXPECT_EQ(j["scans"][2]["time"], "2026-11-20T13:02:00Z");
  const std::string stored = j["scans"][2]["stored"];
  EXPECT_TRUE(before <= stored && stored <= after) << stored;
  ASSERT_EQ(j["events"].size(), 2u);
  EXPECT_EQ(j["events"][1]["time"], "2026-11-20T13:05:00Z");
  const std::string logged = j["events"][1]["logged"];
  EXPECT_TRUE(before <= logged && logged <= after) << logged;
  EXPECT_TRUE(contains(r.out, "time                 stored\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "test v1 1x64 32F             2026-11-20T13:02:00Z " + stored + "\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "score 24.0  track 9  source rec2  logged " + logged + "\n")) << r.out;
  r = run_bodyrec({"gallery", "--gallery", path, "export", "1", (dir / "alice").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = nlohmann::json::parse(read_text(dir / "alice" / "user.json"));
  EXPECT_EQ(j["scans"][2]["stored"], stored);
  EXPECT_EQ(j["events"][1]["logged"], logged);

  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db,
                         "DROP TABLE event_spools; ALTER TABLE events DROP COLUMN logged_ms; "
                         "ALTER TABLE scans DROP COLUMN stored_ms; PRAGMA user_version = 2",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  ASSERT_EQ(run_bodyrec({"gallery", "--gallery", path, "init"}).exit_code, 0);  // upgrades it
  r = run_bodyrec({"gallery", "--gallery", path, "show", "alice", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = last_json_line(r.out);
  EXPECT_EQ(j["scans"][2]["time"], "2026-11-20T13:02:00Z");
  EXPECT_FALSE(j["scans"][2].contains("stored")) << j;
  EXPECT_EQ(j["events"][1]["time"], "2026-11-20T13:05:00Z");
  EXPECT_FALSE(j["events"][1].contains("logged")) << j;
  EXPECT_TRUE(contains(r.out, "test v1 1x64 32F             2026-11-20T13:02:00Z -\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "score 24.0  track 9  source rec2\n")) << r.out;
}

// Numbers print with the precision they carry, as in every other JSON output (io/json_numbers.h).
TEST(GalleryCli, ShowPrintsRoundedNumbers) {
  TempDir dir;
  const std::string path = (dir / "g.db").string();
  {
    GalleryOptions o;
    o.create = true;
    Gallery g(path, o);
    const UserId u = g.enrol(scan_at(View::F, 0.1 * 0.7857, 1, 0));
    Event e;
    e.user = u;
    e.kind = EventKind::kRecognised;
    e.score = 24.123456789;
    e.time = kT0;
    g.log_event(e);
  }
  const RunResult r = run_bodyrec({"gallery", "--gallery", path, "show", "1", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "score 24.1235")) << r.out;
  EXPECT_TRUE(contains(r.out, "\"quality\":0.07857,")) << r.out;
  EXPECT_TRUE(contains(r.out, "\"score\":24.1235")) << r.out;
  EXPECT_FALSE(contains(r.out, "0.07856999")) << r.out;
}

TEST(GalleryCli, ExportWritesTheStoredPngsAndAJson) {
  TempDir dir;
  const std::string path = make_gallery(dir);
  const fs::path out = dir / "alice";
  const RunResult r = run_bodyrec({"gallery", "--gallery", path, "export", "1", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "exported user 1 to " + out.string() + ": 4 scans (4 images, 4 masks")) << r.out;
  const cv::Mat image = cv::imread((out / "SL-image.png").string(), cv::IMREAD_UNCHANGED);
  const GalleryScan original = make_scan(View::SL, 0.75, 3);
  ASSERT_EQ(image.size(), original.image.size());
  EXPECT_EQ(cv::norm(image, original.image, cv::NORM_INF), 0.0);  // lossless
  EXPECT_TRUE(fs::exists(out / "B-mask.png"));
  EXPECT_FALSE(fs::exists(out / "BL-image.png"));  // user 2's
  const auto j = nlohmann::json::parse(read_text(out / "user.json"));
  EXPECT_EQ(j["user"]["label"], "alice");
  EXPECT_EQ(j["scans"][0]["features"]["values"].size(), 64u);
  EXPECT_EQ(j["scans"][0]["features"]["values"][0], 1.0);
  EXPECT_EQ(j["scans"][2]["image_file"], "SL-image.png");
  EXPECT_EQ(j["events"].size(), 2u);
  EXPECT_EQ(fs::status(out).permissions() & fs::perms::all, fs::perms::owner_all);
}

TEST(GalleryCli, ForgetSaysWhatItErased) {
  TempDir dir;
  const std::string path = make_gallery(dir);
  const RunResult r = run_bodyrec({"gallery", "--gallery", path, "forget", "alice", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "forgot user 1: erased 4 scans (4 images, 4 masks, their features), 2 events; " +
                                  path + " vacuumed"))
      << r.out;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["users"], nlohmann::json({1}));
  EXPECT_EQ(j["events"], 2);
  const RunResult list = run_bodyrec({"gallery", "--gallery", path, "list", "--json"});
  EXPECT_EQ(last_json_line(list.out)["users"].size(), 1u);
  const RunResult again = run_bodyrec({"gallery", "--gallery", path, "forget", "1"});
  EXPECT_EQ(again.exit_code, 3);
  EXPECT_EQ(again.err, "bodyrec: error: " + path + ": no user 1\n");
}

TEST(GalleryCli, LabelNamesOneUser) {
  TempDir dir;
  const std::string path = make_gallery(dir);  // user 1 is alice, user 2 has no label
  const RunResult named = run_bodyrec({"gallery", "--gallery", path, "label", "2", "bob"});
  ASSERT_EQ(named.exit_code, 0) << named.err;
  EXPECT_EQ(named.out, "user 2 is labelled bob\n");
  const RunResult show = run_bodyrec({"gallery", "--gallery", path, "show", "bob", "--json"});
  ASSERT_EQ(show.exit_code, 0) << show.err;
  EXPECT_EQ(last_json_line(show.out)["user"]["id"], 2);
  const RunResult taken = run_bodyrec({"gallery", "--gallery", path, "label", "bob", "alice"});
  EXPECT_EQ(taken.exit_code, 3);
  EXPECT_EQ(taken.err, "bodyrec: error: " + path + ": label 'alice' already names user 1\n");
  const RunResult number = run_bodyrec({"gallery", "--gallery", path, "label", "2", "17"});
  EXPECT_EQ(number.exit_code, 2);
  EXPECT_EQ(number.err, "bodyrec: error: LABEL: '17' reads as a user id; give a name with a letter in it\n");
  const RunResult cleared = run_bodyrec({"gallery", "--gallery", path, "label", "alice", ""});
  ASSERT_EQ(cleared.exit_code, 0) << cleared.err;
  EXPECT_EQ(cleared.out, "user 1 has no label now\n");
  EXPECT_EQ(run_bodyrec({"gallery", "--gallery", path, "show", "alice"}).exit_code, 3);
}

TEST(GalleryCli, PurgeNeedsYes) {
  TempDir dir;
  const std::string path = make_gallery(dir);
  const RunResult no = run_bodyrec({"gallery", "--gallery", path, "purge"});
  EXPECT_EQ(no.exit_code, 2);
  EXPECT_EQ(no.err, "bodyrec: error: purge erases all 2 users of " + path + "; run it again with --yes\n");
  const RunResult yes = run_bodyrec({"gallery", "--gallery", path, "purge", "--yes"});
  ASSERT_EQ(yes.exit_code, 0) << yes.err;
  EXPECT_TRUE(contains(yes.out, "erased 2 users, 5 scans (5 images, 5 masks, their features), 3 events")) << yes.out;
  EXPECT_TRUE(contains(run_bodyrec({"gallery", "--gallery", path, "list"}).out, ": 0 users"));
}

TEST(GalleryCli, PruneByRetentionTime) {
  TempDir dir;
  const std::string path = make_gallery(dir);  // everyone last seen on 2026-11-20, less than 10 years ago
  const RunResult keep = run_bodyrec({"gallery", "--gallery", path, "prune", "--unseen-for", "520w"});
  ASSERT_EQ(keep.exit_code, 0) << keep.err;
  EXPECT_TRUE(contains(keep.out, "pruned 0 users")) << keep.out;
  // A zero retention time would erase everyone: that is purge --yes, not a retention policy.
  const RunResult zero = run_bodyrec({"gallery", "--gallery", path, "prune", "--unseen-for", "0s"});
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_EQ(zero.err, "bodyrec: error: --unseen-for: 0s would erase everyone; to do that, run purge --yes\n");
  // --dry-run lists who would go and erases nobody.
  const RunResult dry = run_bodyrec({"gallery", "--gallery", path, "prune", "--unseen-for", "1s", "--dry-run", "--json"});
  ASSERT_EQ(dry.exit_code, 0) << dry.err;
  EXPECT_TRUE(contains(dry.out, "would prune 2 users not seen since ")) << dry.out;
  EXPECT_EQ(last_json_line(dry.out)["users"], nlohmann::json({1, 2}));
  EXPECT_EQ(last_json_line(run_bodyrec({"gallery", "--gallery", path, "list", "--json"}).out)["users"].size(), 2u);
  // Both were last seen in 2026-11: a second's retention drops them all.
  const RunResult gone = run_bodyrec({"gallery", "--gallery", path, "prune", "--unseen-for", "1s", "--json"});
  ASSERT_EQ(gone.exit_code, 0) << gone.err;
  const auto j = last_json_line(gone.out);
  EXPECT_EQ(j["users"], nlohmann::json({1, 2}));
  const RunResult bad = run_bodyrec({"gallery", "--gallery", path, "prune", "--unseen-for", "30 days"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(contains(bad.err, "--unseen-for: expected a whole number with s, m, h, d or w")) << bad.err;
}

TEST(GalleryCli, MissingForeignAndNewerGalleriesAreInputErrors) {
  TempDir dir;
  // The default path is gallery.db in the working directory; it is never created.
  const fs::path old_cwd = fs::current_path();
  fs::current_path(dir.path());
  const RunResult missing = run_bodyrec({"gallery", "list"});
  fs::current_path(old_cwd);
  EXPECT_EQ(missing.exit_code, 3);
  EXPECT_EQ(missing.err, "bodyrec: error: gallery.db: gallery not found\n");
  EXPECT_FALSE(fs::exists(dir / "gallery.db"));
  for (const char* sub : {"show", "forget"}) {
    const RunResult r = run_bodyrec({"gallery", "--gallery", (dir / "none.db").string(), sub, "1"});
    EXPECT_EQ(r.exit_code, 3) << sub;
    EXPECT_FALSE(fs::exists(dir / "none.db"));
  }
  write_text(dir / "video.db", std::string(2000, 'v'));
  const RunResult text = run_bodyrec({"gallery", "--gallery", (dir / "video.db").string(), "list"});
  EXPECT_EQ(text.exit_code, 3);
  EXPECT_TRUE(contains(text.err, (dir / "video.db").string() + ": not an SQLite database")) << text.err;
  EXPECT_EQ(std::count(text.err.begin(), text.err.end(), '\n'), 1);

  const std::string newer = make_gallery(dir);
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(newer.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "PRAGMA user_version = 5", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  const RunResult future = run_bodyrec({"gallery", "--gallery", newer, "show", "1"});
  EXPECT_EQ(future.exit_code, 3);
  EXPECT_EQ(future.err, "bodyrec: error: " + newer +
                            ": gallery schema version 5 is newer than this bodyrec reads (up to 4); use a newer bodyrec\n");
}

}  // namespace
}  // namespace bodyrec::testing
