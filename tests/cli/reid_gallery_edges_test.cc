// The gallery as an output of `reid`: an unwritable one is exit 4 like any output, and a run that fails
// before its first frame leaves no gallery file behind (README "Exit codes and errors").
#include <chrono>
#include <ctime>
#include <filesystem>

#include <gtest/gtest.h>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

fs::path recording_copy(const TempDir& dir) {
  const fs::path& made = synth_recording({"--frames", "3", "--people", "1", "--seed", "4"});
  fs::copy(made, dir / "rec", fs::copy_options::recursive);
  return dir / "rec";
}

// Days from a gallery time ("2026-11-20T13:00:00Z") to now.
double days_ago(const std::string& utc) {
  std::tm tm{};
  strptime(utc.c_str(), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return std::difftime(std::time(nullptr), timegm(&tm)) / 86400.0;
}

// The gallery of a `reid` run over a copy of a 90-frame (3 s) recording whose meta.json was last written
// `ended_ago` before now; its users as `gallery list --json` gives them.
nlohmann::json users_after_run(const TempDir& dir, std::chrono::hours ended_ago) {
  const fs::path& made = synth_recording({"--frames", "90", "--people", "1", "--seed", "4"});
  fs::copy(made, dir / "rec", fs::copy_options::recursive);
  fs::last_write_time(dir / "rec" / "meta.json", fs::file_time_type::clock::now() - ended_ago);
  const fs::path gallery = dir / "g.db";
  const RunResult r = run_bodyrec({"reid", (dir / "rec").string(), "--gallery", gallery.string(), "-q"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const RunResult list = run_bodyrec({"gallery", "--gallery", gallery.string(), "list", "--json"});
  EXPECT_EQ(list.exit_code, 0) << list.err;
  return last_json_line(list.out)["users"];
}

TEST(ReidGallery, AGalleryThatCannotBeCreatedIsAnOutputError) {
  TempDir dir;
  const fs::path rec = recording_copy(dir);
  const std::string gallery = (dir / "no-such-folder" / "g.db").string();
  const RunResult r = run_bodyrec({"reid", rec.string(), "--gallery", gallery, "-q"});
  expect_one_line_error(r, 4, gallery + ": cannot create gallery");
  EXPECT_FALSE(fs::exists(gallery));
}

TEST(ReidGallery, ARunThatFailsOnItsFirstFrameLeavesNoGalleryFile) {
  TempDir dir;
  const fs::path rec = recording_copy(dir);
  write_text(rec / "color" / "000000.png", "not a PNG");
  const fs::path gallery = dir / "g.db";
  const RunResult r = run_bodyrec({"reid", rec.string(), "--gallery", gallery.string(), "-q"});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("000000.png"), std::string::npos) << r.err;
  for (const char* suffix : {"", "-wal", "-shm"}) EXPECT_FALSE(fs::exists(gallery.string() + suffix)) << suffix;

  // A gallery that was there before is kept as it was.
  write_text(gallery, "");
  EXPECT_EQ(run_bodyrec({"reid", rec.string(), "--gallery", gallery.string(), "-q"}).exit_code, 3);
  EXPECT_TRUE(fs::exists(gallery));
}

// Gallery times follow the recording's clock: it ended when its meta.json was last written, and each
// frame's time counts from its start, so a person seen in a 3 s recording finished at 13:00:00 was last
// seen by 13:00:00, however late the run. `created` stays the wall time of the write.
TEST(ReidGallery, TimesFollowTheRecordingsClock) {
  TempDir dir;
  const auto users = users_after_run(dir, std::chrono::hours(24 * 30));
  ASSERT_EQ(users.size(), 1u) << users;
  // 30 days ago, within the recording's 3 s; the wall clock would say today.
  const std::string first = users[0]["first_seen"], last = users[0]["last_seen"], created = users[0]["created"];
  EXPECT_NEAR(days_ago(first), 30.0, 0.01) << first;
  EXPECT_NEAR(days_ago(last), 30.0, 0.01) << last;
  EXPECT_LE(first, last);
  EXPECT_LT(days_ago(created), 0.01) << created;
}

// A file time in the future (a clock set wrong, a copy from elsewhere) never puts a gallery time after
// now, where retention (--prune-unseen-for) would never reach it.
TEST(ReidGallery, ARecordingFromTheFutureEndsNow) {
  TempDir dir;
  const auto users = users_after_run(dir, -std::chrono::hours(24));
  ASSERT_EQ(users.size(), 1u) << users;
  const std::string last = users[0]["last_seen"];
  EXPECT_GE(days_ago(last), 0.0) << last;
  EXPECT_LT(days_ago(last), 0.01) << last;
}

// A gallery filled with one --matcher and then run with another keeps its users: their scans are
// described again from the stored images. Kept without images, that is impossible: a one-line error.
TEST(ReidGallery, AnotherMatcherRecognisesTheSameUsersOrSaysWhyNot) {
  TempDir dir;
  const fs::path& rec = synth_recording({"--people", "2", "--seed", "3", "--frames", "150", "--scenario", "reenter"});
  const std::string gallery = (dir / "g.db").string(), features = (dir / "features.db").string();
  const RunResult lomo = run_bodyrec({"reid", rec.string(), "--matcher", "lomo", "--gallery", gallery, "--json", "-q"});
  ASSERT_EQ(lomo.exit_code, 0) << lomo.err;
  EXPECT_EQ(last_json_line(lomo.out)["users"].get<int>(), 2);
  const RunResult stripes = run_bodyrec({"reid", rec.string(), "--matcher", "stripes", "--gallery", gallery, "--json", "-q"});
  ASSERT_EQ(stripes.exit_code, 0) << stripes.err;
  const auto j = last_json_line(stripes.out);
  EXPECT_EQ(j["users"].get<int>(), 2);
  EXPECT_EQ(j["enrolled"].get<int>(), 0);
  EXPECT_GE(j["recognised"].get<int>(), 2);
  const RunResult show = run_bodyrec({"gallery", "--gallery", gallery, "show", "1"});
  EXPECT_TRUE(contains(show.out, "stripes/")) << show.out;
  EXPECT_FALSE(contains(show.out, "lomo/")) << show.out;

  ASSERT_EQ(run_bodyrec({"reid", rec.string(), "--matcher", "lomo", "--no-images", "--gallery", features, "-q"}).exit_code, 0);
  expect_one_line_error(run_bodyrec({"reid", rec.string(), "--matcher", "stripes", "--gallery", features, "-q"}), 3,
                        features + ": 16 scans (user 1 among them) hold lomo/");
}

// A gallery kept with --no-images stays features only when a later run leaves the flag out.
TEST(ReidGallery, AFeaturesOnlyGalleryStaysSo) {
  TempDir dir;
  const fs::path& rec = synth_recording({"--people", "2", "--seed", "3", "--frames", "150", "--scenario", "reenter"});
  const std::string gallery = (dir / "g.db").string();
  ASSERT_EQ(run_bodyrec({"reid", rec.string(), "--no-images", "--gallery", gallery, "-q", "--max-frames", "70"}).exit_code, 0);
  const RunResult later = run_bodyrec({"reid", rec.string(), "--gallery", gallery, "-q"});
  ASSERT_EQ(later.exit_code, 0) << later.err;
  EXPECT_TRUE(contains(later.err, gallery + " holds features only (kept with --no-images)")) << later.err;
  for (const char* user : {"1", "2"}) {
    const RunResult show = run_bodyrec({"gallery", "--gallery", gallery, "show", user, "--json"});
    ASSERT_EQ(show.exit_code, 0) << show.err;
    EXPECT_FALSE(contains(show.out, "\"image\":true")) << show.out;
    EXPECT_TRUE(contains(show.out, "\"image\":false")) << show.out;
  }
  // A gallery with images is not affected.
  const std::string with = (dir / "with.db").string();
  ASSERT_EQ(run_bodyrec({"reid", rec.string(), "--gallery", with, "-q", "--max-frames", "70"}).exit_code, 0);
  const RunResult again = run_bodyrec({"reid", rec.string(), "--gallery", with, "-q"});
  EXPECT_FALSE(contains(again.err, "features only")) << again.err;
}

}  // namespace
}  // namespace bodyrec::testing
