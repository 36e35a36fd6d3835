// `bodyrec reid` on live and plain-camera sources as a user meets them: --realtime (frames dropped and
// counted when processing falls behind), SIGINT/SIGTERM in the middle of a run, `gallery forget` from another
// process during a run, --sensor without a device, a video, and a recording's colour alone.
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

// 2 s at 30 frames per second.
const fs::path& short_walk() {
  return synth_recording({"--people", "3", "--seed", "21", "--frames", "60", "--scenario", "reenter"});
}
// 8 s at 30 frames per second.
const fs::path& long_walk() {
  return synth_recording({"--people", "3", "--seed", "11", "--frames", "240", "--scenario", "reenter"});
}

std::vector<nlohmann::json> jsonl_lines(const fs::path& file) {
  std::vector<nlohmann::json> out;
  for (const std::string& line : lines_of(read_text(file))) {
    if (line.empty()) continue;
    out.push_back(nlohmann::json::parse(line));  // throws (test error) on a broken line
  }
  return out;
}

std::string integrity(const fs::path& db_path) {
  sqlite3* db = nullptr;
  std::string result = "cannot open";
  if (sqlite3_open_v2(db_path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
    sqlite3_stmt* st = nullptr;
    if (sqlite3_prepare_v2(db, "PRAGMA integrity_check", -1, &st, nullptr) == SQLITE_OK && sqlite3_step(st) == SQLITE_ROW)
      result = reinterpret_cast<const char*>(sqlite3_column_text(st, 0));
    sqlite3_finalize(st);
  }
  sqlite3_close(db);
  return result;
}

// A slow stage (100 ms a frame) behind a 30 fps recording played at its own rate: about two frames in three
// are dropped, each counted, and every frame read is either processed or dropped. Read as fast as it is
// processed (no --realtime), the same slow stage drops nothing.
TEST(ReidLiveCli, RealtimeDropsAndCountsFramesWhenProcessingFallsBehind) {
  TempDir dir;
  const fs::path lines = dir / "r.jsonl";
  RunResult r = run_bodyrec({"reid", short_walk().string(), "--gallery", (dir / "g.db").string(), "--realtime",
                             "--test-delay-ms", "100", "--jsonl", lines.string(), "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = last_json_line(r.out);
  const int frames = j["frames"].get<int>();
  const long dropped = j["dropped"].get<long>();
  EXPECT_GT(dropped, 20);
  EXPECT_LT(frames, 40);
  EXPECT_EQ(frames + dropped, 60);
  EXPECT_FALSE(j["stopped"].get<bool>());
  EXPECT_GE(j["latency_ms_p95"].get<double>(), j["latency_ms_p50"].get<double>());
  const auto parsed = jsonl_lines(lines);
  ASSERT_EQ(parsed.size(), static_cast<size_t>(frames) + 1);  // the frames and the end line
  long last_dropped = 0;
  for (size_t i = 0; i + 1 < parsed.size(); ++i) {
    const auto& f = parsed[i];
    ASSERT_TRUE(f.contains("dropped") && f.contains("arrival") && f.contains("wall")) << f.dump();
    EXPECT_GE(f["dropped"].get<long>(), last_dropped);  // a running count
    last_dropped = f["dropped"].get<long>();
    EXPECT_GE(f["wall"].get<double>() + 1e-3, f["arrival"].get<double>());
  }
  EXPECT_TRUE(parsed.back()["end"].get<bool>());

  r = run_bodyrec({"reid", short_walk().string(), "--gallery", (dir / "h.db").string(), "--test-delay-ms", "20",
                   "--jsonl", (dir / "s.jsonl").string(), "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = last_json_line(r.out);
  EXPECT_EQ(j["frames"].get<int>(), 60);
  EXPECT_EQ(j["dropped"].get<long>(), 0);
  EXPECT_FALSE(jsonl_lines(dir / "s.jsonl").front().contains("arrival"));
}

// SIGINT (Ctrl-C) or SIGTERM in the middle: exit 0, the JSON lines whole to the last, the end line written,
// the gallery intact.
TEST(ReidLiveCli, SignalEndsTheRunCleanly) {
  for (const char* signal : {"INT", "TERM"}) {
    TempDir dir;
    const fs::path lines = dir / "r.jsonl", gallery = dir / "g.db";
    const RunResult r =
        run_bodyrec({"reid", long_walk().string(), "--realtime", "--gallery", gallery.string(), "--jsonl",
                     lines.string(), "--json", "-q"},
                    {"timeout", "--preserve-status", "-s", signal, "4"});
    ASSERT_EQ(r.exit_code, 0) << signal << ": " << r.err;
    const auto j = last_json_line(r.out);
    EXPECT_TRUE(j["stopped"].get<bool>()) << signal;
    EXPECT_GT(j["frames"].get<int>(), 10) << signal;
    EXPECT_LT(j["frames"].get<int>() + j["dropped"].get<long>(), 240) << signal;
    const auto parsed = jsonl_lines(lines);
    ASSERT_FALSE(parsed.empty());
    EXPECT_TRUE(parsed.back().value("end", false)) << signal;
    EXPECT_EQ(integrity(gallery), "ok") << signal;
    EXPECT_GE(j["users"].get<int>(), 1) << signal;
  }
}

// The users named by the events waiting in a spool file (their payloads' "user").
std::set<int> spooled_users(const fs::path& spool) {
  std::set<int> users;
  for (const std::string& line : lines_of(read_text(spool))) {
    const nlohmann::json payload = nlohmann::json::parse(nlohmann::json::parse(line)["payload"].get<std::string>());
    if (payload.contains("user")) users.insert(payload["user"].get<int>());
  }
  return users;
}

// `gallery forget 1` from another process while `reid --realtime` runs: the run goes on to the end, exits
// 0, and user 1 is not written back. Its events that the (unreachable) broker has not taken are taken back
// from the spool: an erased person is never published.
TEST(ReidLiveCli, GalleryForgetDuringARunIsKept) {
  TempDir dir;
  const fs::path gallery = dir / "g.db", forget_out = dir / "forget.txt", spool = dir / "events.spool";
  const std::string script = "(sleep 5; \"$0\" gallery --gallery '" + gallery.string() + "' forget 1 --events-spool '" +
                             spool.string() + "' >'" + forget_out.string() + "' 2>&1; echo \"rc $?\" >>'" +
                             forget_out.string() +
                             "') & \"$0\" \"$@\"; rc=$?; wait; exit $rc";
  const RunResult r = run_bodyrec(
      {"reid", long_walk().string(), "--realtime", "--gallery", gallery.string(), "--json", "-q", "--events",
       "mqtt://127.0.0.1:1/site", "--events-spool", spool.string(), "--events-wait", "0"},
      {"bash", "-c", script});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string forgot = read_text(forget_out);
  ASSERT_TRUE(contains(forgot, "rc 0")) << forgot;
  // The running reid holds the spool: forget leaves it to the run, which withdraws the events itself.
  EXPECT_TRUE(contains(forgot, "events spool " + spool.string() + ": in use by a running reid")) << forgot;
  const auto j = last_json_line(r.out);
  EXPECT_GE(j["events"]["withdrawn"].get<int>(), 1) << j.dump();
  EXPECT_EQ(j["events"]["delivered"].get<int>(), 0);
  const std::set<int> waiting = spooled_users(spool);
  EXPECT_FALSE(waiting.empty());
  EXPECT_EQ(waiting.count(1), 0u) << "user 1's events are still in the spool";
  EXPECT_FALSE(j["stopped"].get<bool>());
  EXPECT_EQ(j["frames"].get<int>() + j["dropped"].get<long>(), 240);
  const RunResult show = run_bodyrec({"gallery", "--gallery", gallery.string(), "show", "1"});
  EXPECT_EQ(show.exit_code, 3) << show.out;
  EXPECT_EQ(integrity(gallery), "ok");
}

// Events an earlier run left undelivered in the spool are taken back at the next run's start when their
// user was erased in between (gallery forget with no run open).
TEST(ReidLiveCli, ASpooledEventOfAForgottenUserIsNeverPublished) {
  TempDir dir;
  const fs::path gallery = dir / "g.db", spool = dir / "events.spool";
  const std::vector<std::string> run = {"reid",   short_walk().string(), "--gallery", gallery.string(), "--json", "-q",
                                        "--events", "mqtt://127.0.0.1:1/site", "--events-spool", spool.string(),
                                        "--events-wait", "0"};
  const RunResult first = run_bodyrec(run);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  ASSERT_EQ(spooled_users(spool).count(1), 1u);
  // Out of forget's reach (it scrubs the spools the gallery lists: ReidLiveCli.GalleryForgetFindsTheSpoolsReidRunsList),
  // as a spool on another machine is.
  fs::rename(spool, dir / "away.spool");
  ASSERT_EQ(run_bodyrec({"gallery", "--gallery", gallery.string(), "forget", "1"}).exit_code, 0);
  fs::rename(dir / "away.spool", spool);
  const RunResult second = run_bodyrec(run);
  ASSERT_EQ(second.exit_code, 0) << second.err;
  const auto j = last_json_line(second.out);
  EXPECT_GE(j["events"]["recovered"].get<int>(), 1);
  EXPECT_GE(j["events"]["withdrawn"].get<int>(), 1);
  const std::set<int> waiting = spooled_users(spool);
  EXPECT_FALSE(waiting.empty());
  EXPECT_EQ(waiting.count(1), 0u);
}

// One SQL statement on an SQLite gallery, as another program (or another machine's bodyrec) would write it.
void sql(const fs::path& gallery, const std::string& statement) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(gallery.c_str(), &db), SQLITE_OK);
  char* message = nullptr;
  const int rc = sqlite3_exec(db, statement.c_str(), nullptr, nullptr, &message);
  EXPECT_EQ(rc, SQLITE_OK) << (message ? message : "") << "\n" << statement;
  sqlite3_free(message);
  sqlite3_close(db);
}

// `gallery forget --events-spool` takes the user's events out of a spool no run holds, at once: their bytes
// do not wait on disk for the next run. A spool file that is not there is an input error before anything
// is erased.
TEST(ReidLiveCli, GalleryForgetScrubsAClosedSpool) {
  TempDir dir;
  const fs::path gallery = dir / "g.db", spool = dir / "events.spool";
  const RunResult first =
      run_bodyrec({"reid", short_walk().string(), "--gallery", gallery.string(), "-q", "--events",
                   "mqtt://127.0.0.1:1/site", "--events-spool", spool.string(), "--events-wait", "0"});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  sql(gallery, "DELETE FROM event_spools");  // a spool the gallery does not list: only --events-spool names it
  const std::set<int> before = spooled_users(spool);
  ASSERT_EQ(before.count(1), 1u);
  expect_one_line_error(
      run_bodyrec({"gallery", "--gallery", gallery.string(), "forget", "1", "--events-spool", (dir / "none").string()}),
      3, (dir / "none").string() + ": no event spool there (--events-spool)");
  ASSERT_EQ(run_bodyrec({"gallery", "--gallery", gallery.string(), "show", "1"}).exit_code, 0);
  RunResult forget = run_bodyrec({"gallery", "--gallery", gallery.string(), "forget", "1", "--json"});
  ASSERT_EQ(forget.exit_code, 0) << forget.err;
  EXPECT_TRUE(last_json_line(forget.out)["spools"].empty()) << forget.out;
  EXPECT_EQ(spooled_users(spool), before);
  forget = run_bodyrec({"gallery", "--gallery", gallery.string(), "forget", "2", "--events-spool", spool.string(), "--json"});
  ASSERT_EQ(forget.exit_code, 0) << forget.err;
  EXPECT_TRUE(contains(forget.out, "events spool " + spool.string() + ": withdrew ")) << forget.out;
  const auto j = last_json_line(forget.out);
  ASSERT_EQ(j["spools"].size(), 1u);
  EXPECT_GE(j["spools"][0]["removed"].get<int>(), 1);
  EXPECT_EQ(j["spools"][0]["status"], "scrubbed");
  const std::set<int> after = spooled_users(spool);
  EXPECT_EQ(after.count(2), 0u);
  EXPECT_EQ(after.size(), before.size() - 1);
}

// A reid run lists its spool in the gallery; gallery forget then scrubs it without being told, says where a
// listed spool is on another machine, keeps one it cannot look at (exit 4 after everything is printed), and
// takes a spool whose file is gone off the list. `gallery spools --scrub` takes out the events of users the
// gallery no longer has (an erasure made elsewhere); `--drop` takes a path off the list; and
// `reid --prune-unseen-for` scrubs the listed spools too.
TEST(ReidLiveCli, GalleryForgetFindsTheSpoolsReidRunsList) {
  TempDir dir;
  const fs::path gallery = dir / "g.db", spool = dir / "events.spool";
  const RunResult first =
      run_bodyrec({"reid", short_walk().string(), "--gallery", gallery.string(), "-q", "--sensor-id", "door", "--events",
                   "mqtt://127.0.0.1:1/site", "--events-spool", spool.string(), "--events-wait", "0"});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const std::set<int> before = spooled_users(spool);
  ASSERT_EQ(before.count(1), 1u);
  ASSERT_GE(before.size(), 2u);
  fs::copy_file(spool, dir / "copy.spool");
  RunResult r = run_bodyrec({"gallery", "--gallery", gallery.string(), "spools", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json j = last_json_line(r.out);
  ASSERT_EQ(j["spools"].size(), 1u) << j;
  EXPECT_EQ(j["spools"][0]["path"], fs::canonical(spool).string());
  EXPECT_EQ(j["spools"][0]["sensor"], "door");
  EXPECT_EQ(j["spools"][0]["place"], "here");
  const std::string machine = j["spools"][0]["machine"];
  ASSERT_FALSE(machine.empty());

  // Another machine's spool (with this machine's host name: names repeat), and one on this machine that
  // cannot be looked at (its folder is not there: an unmounted disk).
  sql(gallery, "INSERT INTO event_spools(machine, host, path, sensor, first_used_ms, last_used_ms) VALUES "
               "('other-" + machine + "', 'robot', '/var/lib/bodyrec/hall.spool', 'hall', 0, 0), ('" + machine +
               "', 'robot', '/nonexistent-disk/lab.spool', 'lab', 0, 0)");
  r = run_bodyrec({"gallery", "--gallery", gallery.string(), "forget", "1", "--json"});
  EXPECT_EQ(r.exit_code, 4) << r.err;
  EXPECT_EQ(r.err, "bodyrec: error: 1 event spool not scrubbed (see above); the erased users' events may still be in it\n");
  EXPECT_TRUE(contains(r.out, "forgot user 1: erased ")) << r.out;
  EXPECT_TRUE(contains(r.out, "events spool " + fs::canonical(spool).string() + ": withdrew ")) << r.out;
  EXPECT_TRUE(contains(r.out, "events spool /var/lib/bodyrec/hall.spool on robot: not on this machine")) << r.out;
  EXPECT_TRUE(contains(r.out, "events spool /nonexistent-disk/lab.spool: not scrubbed: ")) << r.out;
  j = last_json_line(r.out);
  std::map<std::string, std::string> status;
  for (const auto& s : j["spools"]) status[s["path"]] = s["status"];
  EXPECT_EQ(status, (std::map<std::string, std::string>{{fs::canonical(spool).string(), "scrubbed"},
                                                         {"/var/lib/bodyrec/hall.spool", "elsewhere"},
                                                         {"/nonexistent-disk/lab.spool", "error"}}));
  EXPECT_EQ(spooled_users(spool).count(1), 0u);
  EXPECT_EQ(spooled_users(spool).size(), before.size() - 1);
  EXPECT_EQ(run_bodyrec({"gallery", "--gallery", gallery.string(), "show", "1"}).exit_code, 3);  // erased all the same

  r = run_bodyrec({"gallery", "--gallery", gallery.string(), "spools", "--drop", "/nonexistent-disk/lab.spool", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(last_json_line(r.out)["dropped"], 1);
  EXPECT_EQ(last_json_line(r.out)["spools"].size(), 2u);

  // The spool as it was before the erasure (say, restored from a backup): --scrub takes user 1 out again.
  fs::copy_file(dir / "copy.spool", spool, fs::copy_options::overwrite_existing);
  r = run_bodyrec({"gallery", "--gallery", gallery.string(), "spools", "--scrub", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  status.clear();
  j = last_json_line(r.out);
  for (const auto& s : j["scrub"]) status[s["path"]] = s["status"];
  EXPECT_EQ(status, (std::map<std::string, std::string>{{fs::canonical(spool).string(), "scrubbed"},
                                                         {"/var/lib/bodyrec/hall.spool", "elsewhere"}}));
  EXPECT_EQ(spooled_users(spool).count(1), 0u);
  EXPECT_EQ(spooled_users(spool).size(), before.size() - 1);

  // reid --prune-unseen-for (the recording is older than a second): every user goes, and their events
  // leave the listed spools; this run has no --events, so its stdout is untouched.
  r = run_bodyrec({"reid", short_walk().string(), "--gallery", gallery.string(), "--prune-unseen-for", "1s",
                   "--max-frames", "1", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.err, "bodyrec: withdrew ")) << r.err;
  EXPECT_TRUE(contains(r.err, " events of pruned users from the event spool " + fs::canonical(spool).string())) << r.err;
  EXPECT_TRUE(spooled_users(spool).empty());

  // A listed spool whose file is gone: reported and taken off the list.
  fs::remove(spool);
  r = run_bodyrec({"gallery", "--gallery", gallery.string(), "purge", "--yes"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "events spool " + fs::weakly_canonical(spool).string() +
                                  ": no longer there; taken off the gallery's list")) << r.out;
  r = run_bodyrec({"gallery", "--gallery", gallery.string(), "spools"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, ": 1 event spools\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "robot:/var/lib/bodyrec/hall.spool  sensor hall")) << r.out;
  EXPECT_TRUE(contains(r.out, "  elsewhere\n")) << r.out;
}

// Plain-camera options given for an RGB-D recording would be ignored: each is a usage error naming it.
TEST(ReidLiveCli, PlainCameraOptionsOnAnRgbdRecordingAreRefused) {
  TempDir dir;
  const std::string rec = short_walk().string(), gallery = (dir / "g.db").string();
  expect_one_line_error(run_bodyrec({"reid", rec, "--gallery", gallery, "--detector", "hog"}), 2,
                        "--detector is for plain-camera input (a video, images, --camera or --colour-only); " + rec +
                            " is read as RGB-D");
  expect_one_line_error(run_bodyrec({"reid", rec, "--gallery", gallery, "--calibration", "c.xml"}), 2, "--calibration");
  expect_one_line_error(run_bodyrec({"eval", "reid-stream", rec, "--min-hits", "2"}), 2, "--min-hits");
  EXPECT_FALSE(fs::exists(gallery));
  const RunResult colour = run_bodyrec({"reid", rec, "--gallery", gallery, "--colour-only", "--min-hits", "2", "-q"});
  EXPECT_EQ(colour.exit_code, 0) << colour.err;
}

TEST(ReidLiveCli, SensorWithoutADeviceIsOneLineAndExit3) {
  TempDir dir;
  expect_one_line_error(run_bodyrec({"reid", "--sensor", "--gallery", (dir / "g.db").string()}), 3, "sensor");
  expect_one_line_error(run_bodyrec({"segment", "--sensor", "--json"}), 3, "sensor");
  EXPECT_FALSE(fs::exists(dir / "g.db"));
  const RunResult both = run_bodyrec({"reid", short_walk().string(), "--sensor", "--gallery", (dir / "g.db").string()});
  EXPECT_EQ(both.exit_code, 2) << both.err;
  const RunResult none = run_bodyrec({"reid", "--gallery", (dir / "g.db").string()});
  EXPECT_EQ(none.exit_code, 2) << none.err;
}

// A plain camera's video: people found by background subtraction, enrolled, events on stdout as JSON lines.
TEST(ReidLiveCli, VideoEnrolsPeople) {
  if (!fs::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  TempDir dir;
  const RunResult r = run_bodyrec(
      {"reid", vtest_path().string(), "--gallery", (dir / "g.db").string(), "--max-frames", "250", "--jsonl", "-"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  int enrolled = 0, lines = 0;
  std::set<int> users;
  for (const std::string& line : lines_of(r.out)) {
    if (line.empty() || line[0] != '{') continue;
    ++lines;
    const auto f = nlohmann::json::parse(line);
    for (const auto& e : f["events"])
      if (e["kind"] == "enrolled") {
        ++enrolled;
        users.insert(e["user"].get<int>());
      }
  }
  EXPECT_EQ(lines, 251);
  EXPECT_GE(enrolled, 2);
  EXPECT_EQ(users.size(), static_cast<size_t>(enrolled));
}

// A recording's colour alone: the colour pipeline runs and is scored against the truth.
TEST(ReidLiveCli, ColourOnlyRecordingIsScored) {
  const RunResult r = run_bodyrec({"eval", "reid-stream", long_walk().string(), "--colour-only", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_TRUE(j["colour_only"].get<bool>());
  EXPECT_EQ(j["frames"].get<int>(), 240);
  EXPECT_GT(j["body_frames"].get<int>(), 100);
  EXPECT_GT(j["coverage"].get<double>(), 0.3);
  const RunResult camera = run_bodyrec({"reid", long_walk().string(), "--colour-only", "--camera", "0"});
  EXPECT_EQ(camera.exit_code, 2) << camera.err;
}

// The diagnosis with the truth's bodies: every visible person is a body, and with their own masks and
// track ids the colour decisions give each their own user; separability is reported.
TEST(ReidLiveCli, ColourOnlyWithTrueBodies) {
  const RunResult r = run_bodyrec(
      {"eval", "reid-stream", long_walk().string(), "--colour-only", "--true-bodies", "masks", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["identities"].get<int>(), 3);
  EXPECT_EQ(j["merges"].get<int>(), 0);
  EXPECT_EQ(j["splits"].get<int>(), 0);
  EXPECT_GT(j["accuracy"].get<double>(), 0.8);
  EXPECT_GT(j["coverage"].get<double>(), 0.95);
  EXPECT_GT(j["separability"]["probes"].get<int>(), 0);
  EXPECT_GT(j["separability"]["nn_accuracy"].get<double>(), 0.9);
  const RunResult detections = run_bodyrec(
      {"eval", "reid-stream", long_walk().string(), "--colour-only", "--true-bodies", "detections", "--json"});
  ASSERT_EQ(detections.exit_code, 0) << detections.err;
  EXPECT_GT(last_json_line(detections.out)["coverage"].get<double>(), 0.9);
  // Without --colour-only, and with an unknown choice: usage errors.
  EXPECT_EQ(run_bodyrec({"eval", "reid-stream", long_walk().string(), "--true-bodies", "masks"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"eval", "reid-stream", long_walk().string(), "--colour-only", "--true-bodies", "all"}).exit_code,
            2);
}

}  // namespace
}  // namespace bodyrec::testing
