// `bodyrec report` end to end on a small generated groups run: sections, key frames decoded from the
// video, evaluations, --no-images, a re-identification run with a gallery, and its errors with exit codes.
#include <filesystem>

#include <sqlite3.h>

#include <gtest/gtest.h>

#include "report_fixture.h"
#include "test_support.h"

namespace bodyrec::testing {
namespace {

namespace fs = std::filesystem;

int count(const std::string& text, const std::string& part) {
  int n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++n;
  return n;
}

TEST(ReportCommand, WritesOnePageWithKeyFramesAndEvaluations) {
  TempDir dir;
  write_groups_run(dir / "run.jsonl", 40);
  write_magenta_video(dir / "run.avi", 40);
  write_text(dir / "hotel.json", "scene seq_hotel\n{\"pair_f1\":0.81,\"pair_precision\":0.9,\"pair_recall\":0.74,"
                                 "\"pairs\":120,\"scene\":\"seq_hotel\"}\n");
  write_text(dir / "viper.json", "{\"rank1\":0.42,\"rank5\":0.7,\"rank10\":0.8,\"rank20\":0.9,\"map\":0.5,"
                                 "\"probes\":316,\"gallery\":316,\"ms_per_image\":1.2,\"cmc\":[0.42,0.55,0.62,0.67,0.7],"
                                 "\"matcher\":\"stripes\"}\n");
  const RunResult r = run_bodyrec({"report", (dir / "run.jsonl").string(), "--source", (dir / "run.avi").string(),
                                   "--eval", (dir / "hotel.json").string(), "--eval", (dir / "viper.json").string(),
                                   "--key-frames", "4", "--out", (dir / "report.html").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "report.html")) << r.out;
  EXPECT_TRUE(contains(r.out, "groups run, 40 frames, 2 evaluations, 4 key frames")) << r.out;
  const std::string page = read_text(dir / "report.html");
  for (const char* id : {"roles", "groups", "directions", "key-frames", "speed", "evaluations"})
    EXPECT_TRUE(contains(page, std::string("<section id=\"") + id + "\"")) << id;
  EXPECT_EQ(count(page, "class=\"tl-row\""), 3);              // three tracks
  EXPECT_EQ(count(page, "<img alt=\"frame "), 4);             // key frames, embedded
  EXPECT_EQ(count(page, "class=\"point\""), 5);               // CMC ranks
  EXPECT_TRUE(contains(page, ">seq_hotel</text>"));
  EXPECT_FALSE(contains(page, "<script"));

  const RunResult hidden = run_bodyrec({"report", (dir / "run.jsonl").string(), "--source", (dir / "run.avi").string(),
                                        "--no-images", "--out", (dir / "hidden.html").string()});
  ASSERT_EQ(hidden.exit_code, 0) << hidden.err;
  const std::string without = read_text(dir / "hidden.html");
  EXPECT_FALSE(contains(without, "data:image"));
  EXPECT_TRUE(contains(without, "Images left out (--no-images)"));
}

TEST(ReportCommand, GalleryUsersAreRowsOfEightViews) {
  TempDir dir;
  const RunResult r = report_with_gallery(dir, "report.html");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "re-identification run, 30 frames, 0 evaluations, 0 key frames, 2 gallery users")) << r.out;
  const std::string page = read_text(dir / "report.html");
  EXPECT_EQ(count(page, "<section id=\"users\""), 1);
  EXPECT_EQ(count(page, "<div class=\"user\">"), 2);
  EXPECT_EQ(count(page, "<figure class=\"view\">"), 16);
  EXPECT_EQ(count(page, "<img class=\"scan\""), 4);  // alice F, SR, B; bob BL
  EXPECT_EQ(count(page, "<img class=\"scan\" alt=\"BL scan\" src=\"data:image/jpeg;base64,"), 1);
  EXPECT_EQ(count(page, "class=\"slot empty\">no scan</div>"), 12);
  EXPECT_TRUE(contains(page, ">alice</b><span>id 1</span><span>first seen <time>2026-11-20 13:00:00</time></span>"
                             "<span>last seen <time>2026-11-20 13:05:00</time>"));
  EXPECT_TRUE(contains(page, ">bob</b><span>id 2</span><span>first seen <time>2026-11-20 13:10:00</time></span>"
                             "<span>last seen <time>2026-11-20 13:10:00</time>"));
  // Alice has an event in the run; bob has none, so the gallery's enrolment shows in his row.
  EXPECT_TRUE(contains(page, "1 event in this run"));
  EXPECT_EQ(count(page, "class=\"uevent\""), 1);
  EXPECT_TRUE(contains(page, "enrolled BL<time>11-20 13:10:00</time>"));
  EXPECT_FALSE(contains(page, "<script"));
  // The page shows people: owner-only, whatever the umask the test runs under.
  EXPECT_EQ(std::filesystem::status(dir / "report.html").permissions() & std::filesystem::perms::all,
            std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);

  // --no-images: the same rows with placeholders, no pixels.
  const RunResult hidden = report_with_gallery(dir, "hidden.html", {"--no-images"});
  ASSERT_EQ(hidden.exit_code, 0) << hidden.err;
  const std::string without = read_text(dir / "hidden.html");
  EXPECT_FALSE(contains(without, "data:image"));
  EXPECT_EQ(count(without, "<div class=\"user\">"), 2);
  EXPECT_EQ(count(without, "class=\"slot withheld\""), 4);
  EXPECT_EQ(count(without, "class=\"slot empty\">no scan</div>"), 12);

  // A gallery kept without images (features only): placeholders too.
  write_gallery(dir / "features.db", false);
  const RunResult features = run_bodyrec({"report", (dir / "reid.jsonl").string(), "--gallery",
                                          (dir / "features.db").string(), "--out", (dir / "features.html").string()});
  ASSERT_EQ(features.exit_code, 0) << features.err;
  const std::string stored = read_text(dir / "features.html");
  EXPECT_FALSE(contains(stored, "<img class=\"scan\""));
  EXPECT_EQ(count(stored, "no image stored</div>"), 4);

  // A groups run takes a gallery too.
  write_groups_run(dir / "groups.jsonl", 10);
  const RunResult groups = run_bodyrec({"report", (dir / "groups.jsonl").string(), "--gallery", (dir / "g.db").string(),
                                        "--out", (dir / "groups.html").string()});
  ASSERT_EQ(groups.exit_code, 0) << groups.err;
  EXPECT_EQ(count(read_text(dir / "groups.html"), "class=\"uevent\""), 3);  // every gallery event
}

// A re-identification run's key frames come from its input, here a recording's colour frames: each body
// boxed in its user's colour, captions naming who was recognised or enrolled there.
TEST(ReportCommand, ReidRunKeyFramesComeFromItsRecording) {
  TempDir dir;
  const fs::path& rec = synth_recording({"--people", "3", "--seed", "21", "--frames", "60", "--scenario", "reenter"});
  const RunResult run = run_bodyrec(
      {"reid", rec.string(), "--gallery", (dir / "g.db").string(), "--jsonl", (dir / "r.jsonl").string(), "-q"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const RunResult r = run_bodyrec({"report", (dir / "r.jsonl").string(), "--source", rec.string(), "--key-frames", "3",
                                   "--out", (dir / "page.html").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "re-identification run, 60 frames, 0 evaluations, 3 key frames")) << r.out;
  const std::string page = read_text(dir / "page.html");
  EXPECT_EQ(count(page, "<img alt=\"frame "), 3);
  EXPECT_GE(count(page, " enrolled</figcaption>") + count(page, " recognised</figcaption>"), 1);
  EXPECT_TRUE(contains(page, "Each body's box in its user's colour")) << page.substr(0, 2000);
  // Without --source the section says which frames it would show.
  const RunResult bare = run_bodyrec({"report", (dir / "r.jsonl").string(), "--out", (dir / "bare.html").string()});
  ASSERT_EQ(bare.exit_code, 0) << bare.err;
  EXPECT_TRUE(contains(read_text(dir / "bare.html"), "Give --source with the run's input"));
  // A source shorter than the run is not its input: one line, exit 3, no page.
  const fs::path& short_rec = synth_recording({"--people", "1", "--seed", "3", "--frames", "6"});
  const RunResult wrong = run_bodyrec({"report", (dir / "r.jsonl").string(), "--source", short_rec.string(),
                                       "--out", (dir / "wrong.html").string()});
  expect_one_line_error(wrong, 3, short_rec.string() + ": ends before frame ");
  EXPECT_FALSE(fs::exists(dir / "wrong.html"));
}

TEST(ReportCommand, BadInputsGiveOneLineErrors) {
  TempDir dir;
  write_text(dir / "empty.jsonl", "");
  RunResult r = run_bodyrec({"report", (dir / "empty.jsonl").string(), "--out", (dir / "r.html").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "empty.jsonl: no JSON rows")) << r.err;
  EXPECT_EQ(count(r.err, "\n"), 1);

  write_text(dir / "broken.jsonl", "{\"frame\":0,\"people\":[]}\n{\"frame\":1,\"people\":[{\"id\":1}]}\n");
  r = run_bodyrec({"report", (dir / "broken.jsonl").string(), "--out", (dir / "r.html").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "broken.jsonl:2: missing field 'box'")) << r.err;

  write_groups_run(dir / "run.jsonl", 10);
  write_text(dir / "odd.json", "{\"score\":1}\n");
  r = run_bodyrec({"report", (dir / "run.jsonl").string(), "--eval", (dir / "odd.json").string(), "--out",
                   (dir / "r.html").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "odd.json:1: unknown evaluation")) << r.err;

  // Galleries: the store's one-line errors, exit 3, and no report written.
  r = run_bodyrec({"report", (dir / "run.jsonl").string(), "--gallery", (dir / "g.db").string(), "--out",
                   (dir / "r.html").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.err, "bodyrec: error: " + (dir / "g.db").string() + ": gallery not found\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "g.db"));
  write_text(dir / "notes.db", "a text file, not a gallery\n");
  r = run_bodyrec({"report", (dir / "run.jsonl").string(), "--gallery", (dir / "notes.db").string(), "--out",
                   (dir / "r.html").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, (dir / "notes.db").string() + ": not an SQLite database")) << r.err;
  EXPECT_EQ(count(r.err, "\n"), 1);
  write_gallery(dir / "newer.db");
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((dir / "newer.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "PRAGMA user_version = 5", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  r = run_bodyrec({"report", (dir / "run.jsonl").string(), "--gallery", (dir / "newer.db").string(), "--out",
                   (dir / "r.html").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "newer.db: gallery schema version 5 is newer")) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "r.html"));

  write_magenta_video(dir / "short.avi", 3);
  r = run_bodyrec({"report", (dir / "run.jsonl").string(), "--source", (dir / "short.avi").string(), "--out",
                   (dir / "r.html").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "short.avi: ends before frame")) << r.err;

  r = run_bodyrec({"report", (dir / "run.jsonl").string(), "--out", (dir / "no-such-dir" / "r.html").string()});
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_TRUE(contains(r.err, "cannot write the report")) << r.err;
}

}  // namespace
}  // namespace bodyrec::testing
