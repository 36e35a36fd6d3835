// `bodyrec eval groups` and `bodyrec train-groups` on small hand-made scenes: JSON keys, counts, the plain
// rule beside the default (--baseline), nested leave-one-scene-out (--nested), errors.
#include <map>

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

// 20 s annotated every 0.4 s (10 frames of 25 fps): 1-2 walk east side by side `pair_distance` apart,
// 3-4 walk west 0.8 m apart, 5 walks east 2.5 m from 1 (alone), 6-7 stand 1 m apart (not a group), 8
// crosses. Labels: {1,2} and {3,4}.
void write_crowd(const std::filesystem::path& dir, double pair_distance) {
  std::filesystem::create_directories(dir);
  std::string obsmat;
  for (int k = 0; k < 50; ++k) {
    const double t = 0.4 * k;
    const auto row = [&](int id, double x, double y, double vx, double vy) {
      obsmat += std::to_string(10 * k) + " " + std::to_string(id) + " " + std::to_string(x) + " 0 " +
                std::to_string(y) + " " + std::to_string(vx) + " 0 " + std::to_string(vy) + "\n";
    };
    row(1, 1.2 * t, 0, 1.2, 0);
    row(2, 1.2 * t, pair_distance, 1.2, 0);
    row(3, 30 - t, 6, -1, 0);
    row(4, 30 - t, 6.8, -1, 0);
    row(5, 1.2 * t, -2.5, 1.2, 0);
    row(6, 5, 12, 0, 0);
    row(7, 6, 12, 0, 0);
    row(8, 15, -10 + 1.4 * t, 0, 1.4);
  }
  write_text(dir / "obsmat.txt", obsmat);
  write_text(dir / "groups.txt", "1 2\n3 4\n5\n");
}

TEST(EvalGroupsCli, BaselinePrintsThePlainRuleBesideTheDefault) {
  TempDir dir;
  write_crowd(dir / "crowd", 0.6);
  const RunResult r = run_bodyrec({"eval", "groups", "--scene", (dir / "crowd").string(), "--baseline", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["pairs"].get<int>(), 28);
  // The default (built-in learned rule, walking only) finds both pairs and nothing else.
  EXPECT_EQ(j["predicted_pairs"].get<int>(), 2);
  EXPECT_DOUBLE_EQ(j["pair_f1"].get<double>(), 1.0);
  // The plain rule also takes the two people standing 1 m apart: precision 2/3, recall 1, F1 0.8.
  const auto& b = j["baseline"];
  EXPECT_EQ(b["predicted_pairs"].get<int>(), 3);
  EXPECT_EQ(b["true_pairs"].get<int>(), 2);
  EXPECT_NEAR(b["pair_precision"].get<double>(), 2.0 / 3, 1e-6);  // JSON carries 6 digits
  EXPECT_DOUBLE_EQ(b["pair_recall"].get<double>(), 1.0);
  EXPECT_NEAR(b["pair_f1"].get<double>(), 0.8, 1e-6);  // JSON carries 6 digits
  EXPECT_TRUE(contains(r.out, "baseline        rule 2 m / 0.4 m/s, linkage none: precision 0.6667 recall 1.0000 F1 0.8000"))
      << r.out;
  EXPECT_TRUE(contains(r.out, "learned rule: median distance <= 1.3 m and median speed difference <= 0.2 m/s")) << r.out;
}

TEST(EvalGroupsCli, NestedLeaveOneSceneOutOverThreeScenes) {
  TempDir dir;
  write_crowd(dir / "a", 0.6);
  write_crowd(dir / "b", 1.0);
  write_crowd(dir / "c", 1.8);
  const RunResult r = run_bodyrec({"eval", "groups", "--nested", "--scene", (dir / "a").string(), "--scene",
                                   (dir / "b").string(), "--scene", (dir / "c").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["protocol"].get<std::string>(), "nested-loso");
  std::map<std::string, nlohmann::json> by_name;
  for (const auto& m : j["methods"]) by_name[m["method"].get<std::string>()] = m;
  ASSERT_EQ(by_name.size(), 16u);
  // The plain rule takes the standing pair everywhere, and misses c's pair 1.8 m apart.
  const auto& plain = by_name.at("plain rule 2.0 m / 0.4 m/s, linkage none")["scenes"];
  EXPECT_NEAR(plain[0]["pair_f1"].get<double>(), 0.8, 1e-6);  // JSON carries 6 digits
  EXPECT_NEAR(plain[2]["pair_f1"].get<double>(), 0.8, 1e-6);  // JSON carries 6 digits
  // The default family: fitted on a and b (pairs <= 1.0 m apart) it misses c's pair; fitted on the others
  // it scores a and b perfectly.
  const auto& d = by_name.at("learned rule, whole common time, linkage chosen");
  EXPECT_DOUBLE_EQ(d["scenes"][0]["pair_f1"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(d["scenes"][1]["pair_f1"].get<double>(), 1.0);
  EXPECT_NEAR(d["scenes"][2]["pair_recall"].get<double>(), 0.5, 1e-6);  // JSON carries 6 digits
  EXPECT_NEAR(d["mean_pair_f1"].get<double>(), (2 + 2.0 / 3) / 3, 1e-6);  // JSON carries 6 digits
  EXPECT_TRUE(contains(d["scenes"][2]["chosen"].get<std::string>(), "learned rule 1 m / 0.05 m/s")) << d;

  const RunResult two = run_bodyrec({"eval", "groups", "--nested", "--scene", (dir / "a").string(), "--scene",
                                     (dir / "b").string()});
  EXPECT_EQ(two.exit_code, 2) << two.err;
  EXPECT_TRUE(contains(two.err, "--nested needs at least 3 --scene folders")) << two.err;
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
  r = run_bodyrec({"eval", "groups", "--scene", dir.path().string(), "--window", "-1"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(contains(r.err, "must be a positive number of seconds or inf, got '-1'")) << r.err;
  r = run_bodyrec({"train-groups", "--scene", dir.path().string(), "--method", "magic"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = run_bodyrec({"train-groups", "--scene", dir.path().string(), "--method", "pair-model", "--features", "some"});
  EXPECT_EQ(r.exit_code, 2) << r.err;
}

TEST(EvalGroupsCli, TrainGroupsPairModelOnTwoFeatures) {
  TempDir dir;
  write_crowd(dir / "a", 0.6);
  write_crowd(dir / "b", 1.0);
  const auto model = dir / "model.txt";
  RunResult r = run_bodyrec({"train-groups", "--scene", (dir / "a").string(), "--scene", (dir / "b").string(),
                             "--method", "pair-model", "--features", "distance-speed", "--window", "8", "--l2", "1",
                             "--out", model.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string text = read_text(model);
  EXPECT_TRUE(contains(text, "features log_median_distance median_speed_difference\n")) << text;
  EXPECT_TRUE(contains(text, "window_s 8\n")) << text;
  EXPECT_FALSE(contains(text, "\nrule ")) << text;
  r = run_bodyrec({"eval", "groups", "--scene", (dir / "a").string(), "--model", model.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "logistic regression on 2 features over 8 s windows")) << r.out;
}

}  // namespace
}  // namespace bodyrec::testing
