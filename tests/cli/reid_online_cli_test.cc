// `bodyrec reid` and `bodyrec eval reid-stream` as a user meets them: on a synthetic recording where
// three people come in, leave and come back under new tracking ids, and with broken inputs.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <set>
#include <thread>

#include <gtest/gtest.h>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

const fs::path& reenter() {
  return synth_recording({"--people", "3", "--seed", "11", "--frames", "240", "--scenario", "reenter"});
}

TEST(EvalReidStreamCli, ReturningPeopleAreRecognisedWithoutSplitsOrMerges) {
  const RunResult r = run_bodyrec({"eval", "reid-stream", reenter().string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["frames"].get<int>(), 240);
  EXPECT_EQ(j["identities"].get<int>(), 3);
  EXPECT_EQ(j["users"].get<int>(), 3);
  EXPECT_EQ(j["splits"].get<int>(), 0);
  EXPECT_EQ(j["merges"].get<int>(), 0);
  EXPECT_GE(j["accuracy"].get<double>(), 0.95);
  EXPECT_GT(j["body_frames"].get<int>(), 300);
  // The same with body-index slots only (no skeletons: views from depth), and with the depth image only
  // (own segmentation, people followed on the floor).
  for (const char* source : {"body-index", "depth"}) {
    const RunResult b = run_bodyrec({"eval", "reid-stream", reenter().string(), "--bodies-from", source, "--json"});
    ASSERT_EQ(b.exit_code, 0) << source << ": " << b.err;
    const auto jb = last_json_line(b.out);
    EXPECT_EQ(jb["merges"].get<int>(), 0) << source;
    EXPECT_EQ(jb["splits"].get<int>(), 0) << source;
    EXPECT_EQ(jb["users"].get<int>(), 3) << source;
    EXPECT_GE(jb["accuracy"].get<double>(), 0.95) << source;
  }
}

// Six people in view at once (the most a Kinect v2 tracks): six users, none merged or split.
TEST(EvalReidStreamCli, SixBodiesAtOnceAreSixPeople) {
  const fs::path& rec = synth_recording({"--people", "6", "--seed", "5", "--frames", "300", "--scenario", "group"});
  TempDir dir;
  const std::string lines = (dir / "r.jsonl").string();
  const RunResult r = run_bodyrec({"eval", "reid-stream", rec.string(), "--json", "--jsonl", lines});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["identities"].get<int>(), 6);
  EXPECT_EQ(j["users"].get<int>(), 6);
  EXPECT_EQ(j["merges"].get<int>(), 0);
  EXPECT_EQ(j["splits"].get<int>(), 0);
  EXPECT_GE(j["accuracy"].get<double>(), 0.95);  // 0.987 when written
  // Frames with six bodies, each with its own user once decided.
  const std::string text = read_text(lines);
  int six = 0, six_distinct = 0;
  for (size_t at = 0, end; (end = text.find('\n', at)) != std::string::npos; at = end + 1) {
    const auto f = nlohmann::json::parse(text.substr(at, end - at));
    if (!f.contains("bodies") || f["bodies"].size() != 6) continue;
    ++six;
    std::set<int> users;
    for (const auto& b : f["bodies"])
      if (b["user"].is_number_integer()) users.insert(b["user"].get<int>());
    six_distinct += users.size() == 6;
  }
  EXPECT_GE(six, 100);
  EXPECT_GE(six_distinct, 90);
}

// Without skeletons the default (--bodies-from auto) uses the body index, and without that too, its own
// depth segmentation: the same results as forcing each source.
TEST(EvalReidStreamCli, AutoFallsBackToTheBodyIndexThenToOwnSegmentation) {
  TempDir dir;
  const fs::path rec = dir / "rec";
  fs::copy(reenter(), rec, fs::copy_options::recursive);
  const auto drop_stream = [&](const std::string& stream, const std::string& folder) {
    auto meta = nlohmann::json::parse(read_text(rec / "meta.json"));
    auto& streams = meta["streams"];
    streams.erase(std::remove(streams.begin(), streams.end(), stream), streams.end());
    write_text(rec / "meta.json", meta.dump(2));
    fs::remove_all(rec / folder);
  };
  const auto run = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = {"eval", "reid-stream", rec.string(), "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const RunResult r = run_bodyrec(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return last_json_line(r.out);
  };
  const auto forced_index = run({"--bodies-from", "body-index"});
  drop_stream("bodies", "bodies");
  const auto auto_index = run({});
  EXPECT_EQ(auto_index["accuracy"], forced_index["accuracy"]);
  EXPECT_EQ(auto_index["users"].get<int>(), 3);
  const auto forced_depth = run({"--bodies-from", "depth"});
  drop_stream("bodyindex", "bodyindex");
  const auto auto_depth = run({});
  // The same run; only the scoring differs a little: without a body index, segments are paired with true
  // people by box overlap instead of pixel overlap (0.9641 against 0.9647 when written).
  EXPECT_NEAR(auto_depth["accuracy"].get<double>(), forced_depth["accuracy"].get<double>(), 0.005);
  EXPECT_EQ(auto_depth["users"], forced_depth["users"]);
  EXPECT_EQ(auto_depth["merges"].get<int>(), 0);
  EXPECT_GE(auto_depth["accuracy"].get<double>(), 0.95);
  // With neither the body index nor depth, there is nothing to find bodies in.
  const RunResult r = run_bodyrec({"eval", "reid-stream", rec.string(), "--bodies-from", "body-index"});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "needs a body index stream")) << r.err;
}

TEST(EvalReidStreamCli, JsonLinesNameEachBodysTruePerson) {
  TempDir dir;
  const std::string lines = (dir / "r.jsonl").string();
  const RunResult r = run_bodyrec({"eval", "reid-stream", reenter().string(), "--max-frames", "60", "--jsonl", lines});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = read_text(lines);
  int bodies = 0, with_person = 0;
  for (size_t at = 0, end; (end = text.find('\n', at)) != std::string::npos; at = end + 1) {
    const auto j = nlohmann::json::parse(text.substr(at, end - at));
    for (const auto& b : j["bodies"]) {
      ++bodies;
      ASSERT_TRUE(b.contains("person"));
      with_person += b["person"].is_number_integer();
    }
  }
  EXPECT_GT(bodies, 60);
  EXPECT_EQ(with_person, bodies);  // every sensor body is a true person in this recording
}

TEST(ReidCli, EnrolsOnceThenRecognisesFromThePersistentGallery) {
  TempDir dir;
  const std::string gallery = (dir / "g.db").string(), lines = (dir / "r.jsonl").string();
  RunResult r = run_bodyrec({"reid", reenter().string(), "--gallery", gallery, "--jsonl", lines, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = last_json_line(r.out);
  EXPECT_EQ(j["enrolled"].get<int>(), 3);
  EXPECT_EQ(j["users"].get<int>(), 3);
  EXPECT_GE(j["recognised"].get<int>(), 3);  // everyone comes back once
  EXPECT_GE(j["left"].get<int>(), 6);
  EXPECT_TRUE(contains(r.out, "enrolled user 1"));
  // One JSON line per frame plus the end line with the last departures.
  const std::string text = read_text(lines);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 241);
  const auto end = last_json_line(text);
  EXPECT_TRUE(end["end"].get<bool>());
  EXPECT_EQ(end["frame"].get<int>(), 240);
  // A middle frame: bodies with track, user, view, box; stage times.
  const auto mid = nlohmann::json::parse(text.substr(0, text.find('\n', text.size() / 2)).substr(text.rfind('\n', text.size() / 2) + 1));
  ASSERT_TRUE(mid.contains("bodies"));
  for (const char* key : {"frame", "time", "events", "ms"}) EXPECT_TRUE(mid.contains(key)) << key;
  for (const auto& b : mid["bodies"])
    for (const char* key : {"track", "user", "view", "box"}) EXPECT_TRUE(b.contains(key)) << key;
  // Second run on the same gallery: nobody new.
  r = run_bodyrec({"reid", reenter().string(), "--gallery", gallery, "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = last_json_line(r.out);
  EXPECT_EQ(j["enrolled"].get<int>(), 0);
  EXPECT_EQ(j["users"].get<int>(), 3);
  EXPECT_GE(j["recognised"].get<int>(), 6);
  // The gallery command sees them, and their events.
  r = run_bodyrec({"gallery", "list", "--gallery", gallery});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "3 users")) << r.out;
}

// The thesis's matcher compares a scan with the same and the complementary views unless told otherwise.
TEST(ReidCli, KazeComparesTheSameAndComplementaryViewsByDefault) {
  TempDir dir;
  RunResult r = run_bodyrec({"reid", reenter().string(), "--gallery", (dir / "k.db").string(), "--matcher", "kaze",
                             "--max-frames", "90", "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = last_json_line(r.out);
  EXPECT_EQ(j["matcher"], "kaze");
  EXPECT_EQ(j["match_views"], "near");
  EXPECT_GE(j["enrolled"].get<int>(), 1);
  EXPECT_EQ(j["frames"].get<int>(), 90);
  r = run_bodyrec({"reid", reenter().string(), "--gallery", (dir / "a.db").string(), "--matcher", "kaze",
                   "--match-views", "all", "--max-frames", "10", "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(last_json_line(r.out)["match_views"], "all");
  r = run_bodyrec({"reid", reenter().string(), "--gallery", (dir / "s.db").string(), "--max-frames", "10", "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(last_json_line(r.out)["matcher"], "stripes");
  EXPECT_EQ(last_json_line(r.out)["match_views"], "all");
}

// The gallery's event history is capped per user, and retention forgets users before the run.
TEST(ReidCli, EventCapAndRetentionKeepTheGalleryBounded) {
  TempDir dir;
  const std::string gallery = (dir / "g.db").string();
  RunResult r = run_bodyrec({"reid", reenter().string(), "--gallery", gallery, "--max-events-per-user", "2", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_bodyrec({"reid", reenter().string(), "--gallery", gallery, "--max-events-per-user", "2", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* user : {"1", "2", "3"}) {
    r = run_bodyrec({"gallery", "show", user, "--gallery", gallery, "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(last_json_line(r.out)["events"].size(), 2u) << user;  // two runs give each user more than 2
  }
  r = run_bodyrec({"reid", reenter().string(), "--gallery", gallery, "--max-events-per-user", "-1"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  // Everyone was last seen over a second ago: a 1 s retention forgets them, and the run enrols anew.
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  r = run_bodyrec({"reid", reenter().string(), "--gallery", gallery, "--prune-unseen-for", "1s", "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(last_json_line(r.out)["enrolled"].get<int>(), 3);
  EXPECT_EQ(last_json_line(r.out)["users"].get<int>(), 3);
  r = run_bodyrec({"gallery", "list", "--gallery", gallery, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(contains(r.out, "\"id\":1,")) << r.out;  // ids are never reused: users 4, 5, 6
}

TEST(ReidCli, NoImagesKeepsNoPixels) {
  TempDir dir;
  const std::string gallery = (dir / "g.db").string();
  const RunResult r = run_bodyrec({"reid", reenter().string(), "--gallery", gallery, "--no-images", "-q", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(last_json_line(r.out)["users"].get<int>(), 3);
  std::string bytes = read_text(gallery);
  if (fs::exists(gallery + "-wal")) bytes += read_text(gallery + "-wal");
  EXPECT_EQ(bytes.find("\x89PNG"), std::string::npos);
}

TEST(ReidCli, BadInputsSayWhatIsWrong) {
  TempDir dir;
  RunResult r = run_bodyrec({"reid", (dir / "missing").string(), "--gallery", (dir / "g.db").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "missing")) << r.err;
  write_text(dir / "not.db", "these are not the people you are looking for\n");
  r = run_bodyrec({"reid", reenter().string(), "--gallery", (dir / "not.db").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "not.db")) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  r = run_bodyrec({"reid", reenter().string(), "--gallery", (dir / "g.db").string(), "--decide-after", "0"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = run_bodyrec({"reid", reenter().string(), "--gallery", (dir / "g.db").string(), "--matcher", "eigenfaces"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = run_bodyrec({"reid", reenter().string(), "--gallery", (dir / "g.db").string(), "--stature-weight", "-1"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "stature")) << r.err;
  r = run_bodyrec({"eval", "reid-stream", reenter().string(), "--bodies-from", "skeleton", "--max-frames", "5",
                   "--matcher", "stripes", "--model", "x.yml"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
}

TEST(ReidCli, ABrokenFrameStopsWithItsNameAndKeepsTheFramesBefore) {
  TempDir dir;
  const fs::path rec = dir / "rec";
  fs::copy(reenter(), rec, fs::copy_options::recursive);
  write_text(rec / "depth" / "000050.png", "truncated");
  const std::string lines = (dir / "r.jsonl").string();
  const RunResult r = run_bodyrec({"reid", rec.string(), "--gallery", (dir / "g.db").string(), "--jsonl", lines, "-q"});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "000050.png")) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const std::string text = read_text(lines);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 50);
}

}  // namespace
}  // namespace bodyrec::testing
