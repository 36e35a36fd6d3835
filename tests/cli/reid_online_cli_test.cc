// `bodyrec reid` and `bodyrec eval reid-stream` as a user meets them: on a synthetic recording where
// three people come in, leave and come back under new tracking ids, and with broken inputs.
#include <algorithm>
#include <filesystem>

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
