// The gallery as an output of `reid`: an unwritable one is exit 4 like any output, and a run that fails
// before its first frame leaves no gallery file behind (README "Exit codes and errors").
#include <algorithm>
#include <ctime>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>

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

// "2026-12-07T04:26:30Z" as Unix seconds.
double unix_seconds(const std::string& iso) {
  std::tm tm{};
  std::istringstream in(iso);
  in >> std::get_time(&tm, "%Y-%m-%dT%H:%M:%SZ");
  return static_cast<double>(timegm(&tm));
}

// 600 frames at 30 frames/s are 20 s of recording, processed in a few seconds: first and last seen follow
// the recording's clock, not the time the run took.
TEST(ReidGallery, FirstAndLastSeenFollowTheRecordingsClock) {
  TempDir dir;
  const fs::path& rec = synth_recording({"--scenario", "reenter", "--people", "2", "--frames", "600", "--seed", "2"});
  const std::string gallery = (dir / "g.db").string(), jsonl = (dir / "reid.jsonl").string();
  ASSERT_EQ(run_bodyrec({"reid", rec.string(), "--gallery", gallery, "--jsonl", jsonl, "-q"}).exit_code, 0);
  // user -> recording seconds of its first and last event, and of the first and last frame a body was it
  std::map<int, std::pair<double, double>> events, bodies;
  const auto note = [](std::map<int, std::pair<double, double>>& m, int user, double t) {
    if (!m.count(user)) m[user] = {t, t};
    m[user].second = t;
  };
  for (const std::string& line : lines_of(read_text(jsonl))) {
    const nlohmann::json j = nlohmann::json::parse(line);
    if (!j.contains("time")) continue;
    const double t = j["time"].get<double>();
    for (const auto& e : j.value("events", nlohmann::json::array())) note(events, e["user"].get<int>(), t);
    for (const auto& b : j.value("bodies", nlohmann::json::array()))
      if (b["user"].is_number()) note(bodies, b["user"].get<int>(), t);
  }
  const RunResult list = run_bodyrec({"gallery", "--gallery", gallery, "list", "--json"});
  ASSERT_EQ(list.exit_code, 0) << list.err;
  const nlohmann::json users = last_json_line(list.out)["users"];
  ASSERT_EQ(users.size(), 2u) << list.out;
  for (const auto& u : users) {
    const int id = u["id"].get<int>();
    const double low = events.at(id).second - events.at(id).first;
    const double high = std::max(events.at(id).second, bodies.at(id).second) -
                        std::min(events.at(id).first, bodies.at(id).first);
    ASSERT_GT(low, 8.0) << "the recording should keep user " << id << " in view for a while";
    const double span = unix_seconds(u["last_seen"]) - unix_seconds(u["first_seen"]);
    EXPECT_GE(span, low - 1.01) << u.dump();  // the list prints whole seconds
    EXPECT_LE(span, high + 1.01) << u.dump();
  }
}

}  // namespace
}  // namespace bodyrec::testing
