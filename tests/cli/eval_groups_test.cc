// `bodyrec eval groups` and `bodyrec train-groups` on a small hand-made scene: JSON keys, counts, errors.
#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

// Six people, 12 samples 10 frames (0.4 s) apart: 1-2 walk side by side, 3-4 side by side the other way,
// 5 walks alone across, 6 stands. Labels: {1,2} and {3,4}.
void write_scene(const TempDir& dir) {
  std::string obsmat;
  for (int k = 0; k < 12; ++k) {
    const double t = 0.4 * k;
    const auto row = [&](int id, double x, double y, double vx, double vy) {
      obsmat += std::to_string(10 * k) + " " + std::to_string(id) + " " + std::to_string(x) + " 0 " +
                std::to_string(y) + " " + std::to_string(vx) + " 0 " + std::to_string(vy) + "\n";
    };
    row(1, 1.3 * t, 0, 1.3, 0);
    row(2, 1.3 * t, 0.7, 1.3, 0);
    row(3, 12 - 1.1 * t, 4, -1.1, 0);
    row(4, 12 - 1.1 * t, 4.6, -1.1, 0);
    row(5, 4, -5 + 1.5 * t, 0, 1.5);
    row(6, 9, -3, 0, 0);
  }
  write_text(dir / "obsmat.txt", obsmat);
  write_text(dir / "groups.txt", "1 2\n3 4\n5\n6\n");
}

TEST(EvalGroupsCli, ScoresPairsOfAHandMadeScene) {
  TempDir dir;
  write_scene(dir);
  for (const char* method : {"learned", "threshold"}) {
    const RunResult r = run_bodyrec({"eval", "groups", "--scene", dir.path().string(), "--method", method, "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = last_json_line(r.out);
    EXPECT_EQ(j["pairs"].get<int>(), 15) << method;  // all 6 people are seen together: 6*5/2
    EXPECT_EQ(j["labelled_pairs"].get<int>(), 2) << method;
    EXPECT_DOUBLE_EQ(j["pair_precision"].get<double>(), 1.0) << method;
    EXPECT_DOUBLE_EQ(j["pair_recall"].get<double>(), 1.0) << method;
    EXPECT_DOUBLE_EQ(j["pair_f1"].get<double>(), 1.0) << method;
  }
}

TEST(EvalGroupsCli, TrainedModelFileIsUsedAndBadInputIsReported) {
  TempDir dir;
  write_scene(dir);
  const auto model = dir / "model.txt";
  RunResult r = run_bodyrec({"train-groups", "--scene", dir.path().string(), "--out", model.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(read_text(model), "bodyrec-pair-model 1"));
  r = run_bodyrec({"eval", "groups", "--scene", dir.path().string(), "--model", model.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "(includes this scene)")) << r.out;
  EXPECT_DOUBLE_EQ(last_json_line(r.out)["pair_f1"].get<double>(), 1.0);

  r = run_bodyrec({"eval", "groups", "--scene", dir.path().string(), "--method", "magic"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = run_bodyrec({"eval", "groups", "--scene", dir.path().string(), "--linkage", "complete"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = run_bodyrec({"eval", "groups", "--scene", (dir / "none").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  write_text(dir / "groups.txt", "1 2\n3 four\n");
  r = run_bodyrec({"eval", "groups", "--scene", dir.path().string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "groups.txt:2: person id is not a non-negative integer: 'four'")) << r.err;
  r = run_bodyrec({"eval", "groups", "--scene", dir.path().string(), "--model", (dir / "nomodel.txt").string()});
  EXPECT_EQ(r.exit_code, 3) << r.err;
}

}  // namespace
}  // namespace bodyrec::testing
