// `bodyrec report` end to end on a small generated groups run: sections, key frames decoded from the
// video, evaluations, --no-images, and its errors with exit codes.
#include <gtest/gtest.h>

#include "report_fixture.h"
#include "test_support.h"

namespace bodyrec::testing {
namespace {

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

  r = run_bodyrec({"report", (dir / "run.jsonl").string(), "--gallery", (dir / "g.db").string(), "--out",
                   (dir / "r.html").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--gallery is not available yet")) << r.err;

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
