// `bodyrec eval reid` and `bodyrec train-reid` as a user meets them: on a tiny two-camera set of
// generated person images, with broken inputs.
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/model_files.h"
#include "bodyrec/reid/learned_matcher.h"
#include "bodyrec/reid/xqda.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

// A person: shirt and trousers of the identity's colours, per-image noise; camera 2 is darker and
// shifted. 10 identities in both cameras (p00..p09), p10 only in camera 2 (a distractor).
cv::Mat person(int id, int cam) {
  cv::RNG colours(static_cast<uint64_t>(100 + id));
  const cv::Scalar shirt(colours.uniform(0, 256), colours.uniform(0, 256), colours.uniform(0, 256));
  const cv::Scalar trousers(colours.uniform(0, 256), colours.uniform(0, 256), colours.uniform(0, 256));
  cv::Mat image(128, 48, CV_8UC3, cv::Scalar(120, 130, 125));
  const int dx = cam == 1 ? 3 : 0;
  cv::rectangle(image, cv::Rect(10 + dx, 12, 26, 50), shirt, cv::FILLED);
  cv::rectangle(image, cv::Rect(13 + dx, 62, 20, 58), trousers, cv::FILLED);
  cv::circle(image, {23 + dx, 7}, 6, cv::Scalar(80, 110, 160), cv::FILLED);
  if (cam == 1) image.convertTo(image, -1, 0.8, 0);
  cv::Mat noise(image.size(), CV_8UC3);
  cv::RNG rng(static_cast<uint64_t>(id * 2 + cam));
  rng.fill(noise, cv::RNG::UNIFORM, 0, 20);
  return image + noise;
}

const fs::path& person_set() {
  static TempDir dir;
  static const fs::path root = [] {
    for (int id = 0; id <= 10; ++id)
      for (int cam = 0; cam < 2; ++cam) {
        if (id == 10 && cam == 0) continue;
        const fs::path p = dir / ("cam" + std::to_string(cam + 1)) / ("p" + std::string(id < 10 ? "0" : "") +
                                                                      std::to_string(id) + ".png");
        fs::create_directories(p.parent_path());
        cv::imwrite(p.string(), person(id, cam));
      }
    return dir.path();
  }();
  return root;
}

std::vector<std::string> eval_args(const std::vector<std::string>& extra) {
  std::vector<std::string> a = {"eval", "reid", "--root", person_set().string(), "--id-regex", "/p(\\d+)\\.png$",
                                "--cam-regex", "^cam(\\d)/", "--json"};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

TEST(EvalReidCli, ScoresTheUnlearnedFallbackWithDistractors) {
  const RunResult r = run_bodyrec(eval_args({"--matcher", "lomo", "--train-ids", "4", "--splits", "3"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["probes"].get<int>(), 6);   // 10 in both cameras - 4 for training
  EXPECT_EQ(j["gallery"].get<int>(), 7);  // their camera-2 images + the distractor
  EXPECT_DOUBLE_EQ(j["rank1"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["rank5"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(j["map"].get<double>(), 1.0);
  EXPECT_GT(j["ms_per_image"].get<double>(), 0.0);
  for (const char* key : {"rank10", "rank20"}) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_TRUE(contains(r.out, "unlearned"));
}

TEST(EvalReidCli, DefaultTrainsXqdaAndKazeIsMeasured) {
  const RunResult d = run_bodyrec(eval_args({"--train-ids", "5", "--splits", "2"}));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_TRUE(contains(d.out, "XQDA"));
  EXPECT_GE(last_json_line(d.out)["rank1"].get<double>(), 0.8);
  // How the learned same-person threshold does on the test pairs is reported (printed and in the JSON).
  EXPECT_TRUE(contains(d.out, "threshold     accepts"));
  EXPECT_GE(last_json_line(d.out)["same_accepted"].get<double>(), 0.5);
  EXPECT_GE(last_json_line(d.out)["different_rejected"].get<double>(), 0.25);
  const RunResult k = run_bodyrec(eval_args({"--matcher", "kaze", "--train-ids", "5", "--splits", "1"}));
  ASSERT_EQ(k.exit_code, 0) << k.err;
  EXPECT_EQ(last_json_line(k.out)["probes"].get<int>(), 5);
  EXPECT_TRUE(contains(k.out, "KAZE"));
}

TEST(TrainReidCli, WritesAModelThatEvalReidUses) {
  TempDir dir;
  const std::string model = (dir / "reid.yml").string();
  const RunResult t = run_bodyrec({"train-reid", "--root", person_set().string(), "--id-regex", "/p(\\d+)\\.png$",
                                   "--cam-regex", "^cam(\\d)/", "--out", model});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  ASSERT_TRUE(fs::exists(model));
  const RunResult r = run_bodyrec(eval_args({"--model", model, "--train-ids", "0", "--splits", "1"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(last_json_line(r.out)["probes"].get<int>(), 10);
  EXPECT_DOUBLE_EQ(last_json_line(r.out)["rank1"].get<double>(), 1.0);  // trained on these very people
  const RunResult bad = run_bodyrec(eval_args({"--model", (dir / "none.yml").string()}));
  EXPECT_EQ(bad.exit_code, 3);
}

// --swap-cameras: probes from the second camera. The distractor p10 (second camera only) is no longer in
// the gallery, and the first camera has no distractor: 6 probes against 6 gallery images.
TEST(EvalReidCli, SwapCamerasTakesProbesFromTheSecondCamera) {
  const RunResult r = run_bodyrec(eval_args({"--matcher", "lomo", "--train-ids", "4", "--splits", "3", "--swap-cameras"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["probes"].get<int>(), 6);
  EXPECT_EQ(j["gallery"].get<int>(), 6);
  EXPECT_TRUE(contains(r.out, "cameras '2' -> '1'")) << r.out;
  EXPECT_EQ(j["rank1_per_split"].size(), 3u);
  EXPECT_EQ(j["map_per_split"].size(), 3u);
}

// --open-set: of the 6 test people half are enrolled; the gallery holds their camera-2 images and the
// distractor p10, the probes are all 6 (3 enrolled, 3 strangers).
TEST(EvalReidCli, OpenSetEnrolsHalfTheTestPeople) {
  const RunResult r = run_bodyrec(eval_args({"--matcher", "lomo", "--train-ids", "4", "--splits", "3", "--open-set"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["enrolled_probes"].get<int>(), 3);
  EXPECT_EQ(j["stranger_probes"].get<int>(), 3);
  EXPECT_DOUBLE_EQ(j["rank1_closed"].get<double>(), 1.0);
  for (const char* key : {"dir_far1", "dir_far10", "dir_at_threshold", "far_at_threshold", "missed_at_threshold"}) {
    ASSERT_TRUE(j.contains(key)) << key;
    EXPECT_GE(j[key].get<double>(), 0.0) << key;
    EXPECT_LE(j[key].get<double>(), 1.0) << key;
    EXPECT_EQ(j[std::string(key) + "_per_split"].size(), 3u) << key;
  }
  // With 3 strangers FAR 1 % and 10 % both accept none: the same threshold.
  EXPECT_DOUBLE_EQ(j["dir_far1"].get<double>(), j["dir_far10"].get<double>());
  EXPECT_TRUE(contains(r.out, "open set")) << r.out;
  // The closed-set figures are unchanged by the flag.
  const auto closed = last_json_line(run_bodyrec(eval_args({"--matcher", "lomo", "--train-ids", "4", "--splits", "3"})).out);
  EXPECT_EQ(j["rank1_per_split"], closed["rank1_per_split"]);
  EXPECT_FALSE(closed.contains("dir_far1"));
  // Probes from camera 2: the first camera has no distractor, the gallery only the enrolled.
  const auto swapped = last_json_line(
      run_bodyrec(eval_args({"--matcher", "lomo", "--train-ids", "4", "--splits", "2", "--open-set", "--swap-cameras"})).out);
  EXPECT_EQ(swapped["enrolled_probes"].get<int>(), 3);
  EXPECT_EQ(swapped["stranger_probes"].get<int>(), 3);
  // One test person cannot be split into enrolled people and strangers.
  expect_one_line_error(run_bodyrec(eval_args({"--matcher", "lomo", "--train-ids", "9", "--open-set"})), 2, "--open-set");
}

// --resize resamples every image first: to the size the images have, nothing changes; to another size
// the figures are measured on the resampled images.
TEST(EvalReidCli, ResizeResamplesEveryImageFirst) {
  const std::vector<std::string> base = {"--matcher", "lomo", "--train-ids", "4", "--splits", "2"};
  const RunResult plain = run_bodyrec(eval_args(base));
  std::vector<std::string> same = base, bigger = base;
  same.insert(same.end(), {"--resize", "48x128"});
  bigger.insert(bigger.end(), {"--resize", "128x256"});
  const RunResult as_is = run_bodyrec(eval_args(same)), resized = run_bodyrec(eval_args(bigger));
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  ASSERT_EQ(as_is.exit_code, 0) << as_is.err;
  ASSERT_EQ(resized.exit_code, 0) << resized.err;
  // Ranks are perfect on this easy set either way; the distances (shares of pairs within the threshold)
  // show whether the images changed.
  auto rates = [](const RunResult& run) {
    const auto j = last_json_line(run.out);
    return std::vector<double>{j["same_accepted"].get<double>(), j["different_rejected"].get<double>()};
  };
  EXPECT_EQ(rates(as_is), rates(plain));
  EXPECT_NE(rates(resized), rates(plain)) << resized.out;
  EXPECT_EQ(last_json_line(resized.out)["probes"].get<int>(), 6);
  EXPECT_TRUE(contains(resized.out, "resampled to 128x256")) << resized.out;
  for (const char* bad : {"0x5", "48", "48x", "x128", "-48x128", "48x128x3", "4.5x10", "99999x5", "48 x128", "+48x128"}) {
    std::vector<std::string> args = base;
    args.insert(args.end(), {"--resize", bad});
    const RunResult r = run_bodyrec(eval_args(args));
    expect_one_line_error(r, 2, "--resize");
  }
}

// The published recipe is its own matcher: trained by train-reid, used with --model; a model of one
// matcher is refused by the other; matchers that learn need training people or a model.
TEST(TrainReidCli, PublishedRecipeModelsAndWrongMatchers) {
  TempDir dir;
  const std::string model = (dir / "published.yml.gz").string();
  const std::vector<std::string> data = {"--root", person_set().string(), "--id-regex", "/p(\\d+)\\.png$",
                                         "--cam-regex", "^cam(\\d)/"};
  std::vector<std::string> train = {"train-reid", "--matcher", "lomo-xqda", "--out", model};
  train.insert(train.end(), data.begin(), data.end());
  const RunResult t = run_bodyrec(train);
  ASSERT_EQ(t.exit_code, 0) << t.err;
  const RunResult r = run_bodyrec(eval_args({"--matcher", "lomo-xqda", "--model", model, "--splits", "1", "--train-ids", "0"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_DOUBLE_EQ(last_json_line(r.out)["rank1"].get<double>(), 1.0);
  EXPECT_TRUE(contains(r.out, "as published")) << r.out;
  expect_one_line_error(run_bodyrec(eval_args({"--matcher", "default", "--model", model})), 3, "lomo4");
  std::vector<std::string> unlearned = {"train-reid", "--matcher", "lomo", "--out", (dir / "x.yml").string()};
  unlearned.insert(unlearned.end(), data.begin(), data.end());
  expect_one_line_error(run_bodyrec(unlearned), 2, "lomo");
  expect_one_line_error(run_bodyrec(eval_args({"--matcher", "lomo-xqda", "--train-ids", "0"})), 2, "--model");
}

// default-full (the default matcher's variants on the unsketched features) ships no model: train-reid
// makes one, eval reid and reid use it with --model, and a default model is not one of its.
TEST(TrainReidCli, TheFullDefaultMatcherTrainsAndNeedsItsModel) {
  TempDir dir;
  const std::string model = (dir / "full.yml.gz").string();
  std::vector<std::string> train = {"train-reid", "--matcher", "default-full", "--out", model, "--root",
                                    person_set().string(), "--id-regex", "/p(\\d+)\\.png$", "--cam-regex", "^cam(\\d)/"};
  const RunResult t = run_bodyrec(train);
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_TRUE(contains(t.err, "on the full features")) << t.err;
  const RunResult r = run_bodyrec(eval_args({"--matcher", "default-full", "--model", model, "--splits", "1", "--train-ids", "0"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_DOUBLE_EQ(last_json_line(r.out)["rank1"].get<double>(), 1.0);
  EXPECT_TRUE(contains(r.out, "on the full features")) << r.out;
  expect_one_line_error(run_bodyrec(eval_args({"--matcher", "default", "--model", model})), 3, "'lomo4-gog1'");
  expect_one_line_error(run_bodyrec(eval_args({"--matcher", "default-full", "--train-ids", "0"})), 2, "--model");
  const fs::path& rec = synth_recording({"--people", "2", "--seed", "3", "--frames", "60", "--scenario", "reenter"});
  expect_one_line_error(run_bodyrec({"reid", rec.string(), "--matcher", "default-full", "--gallery",
                                     (dir / "g.db").string()}),
                        2, "--model");
}

// The default matcher's model is found without a flag ($BODYREC_MODELS first, then the shipped models/).
TEST(TrainReidCli, TheDefaultModelIsFoundWithoutAFlag) {
  TempDir dir;
  const std::string model = (dir / "reid-default.yml.gz").string();
  const RunResult t = run_bodyrec({"train-reid", "--root", person_set().string(), "--id-regex", "/p(\\d+)\\.png$",
                                   "--cam-regex", "^cam(\\d)/", "--out", model});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_TRUE(contains(t.err, "chosen by 4-fold cross-validation")) << t.err;
  const fs::path& rec = synth_recording({"--people", "2", "--seed", "3", "--frames", "60", "--scenario", "reenter"});
  const RunResult r = run_bodyrec({"eval", "reid-stream", rec.string(), "--bodies-from", "skeleton", "--max-frames",
                                   "40", "--matcher", "default", "--json"},
                                  {"env", "BODYREC_MODELS=" + dir.path().string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(last_json_line(r.out)["matcher"], "default");
  // eval reid with no training people: the default matcher uses that model as is, on every person.
  const RunResult e = run_bodyrec(eval_args({"--train-ids", "0", "--splits", "1"}),
                                  {"env", "BODYREC_MODELS=" + dir.path().string()});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_EQ(last_json_line(e.out)["probes"].get<int>(), 10);
  EXPECT_DOUBLE_EQ(last_json_line(e.out)["rank1"].get<double>(), 1.0);
  EXPECT_TRUE(contains(e.out, "matcher       variant ")) << e.out;
  EXPECT_FALSE(contains(e.out, "split 0")) << e.out;
  // Scoring a model on the data it may have been trained on is said on stderr.
  EXPECT_TRUE(contains(e.err, (dir / "reid-default.yml.gz").string() + " is used as is on every person")) << e.err;
  // The published recipe ships no model: online it needs --model.
  expect_one_line_error(run_bodyrec({"eval", "reid-stream", rec.string(), "--bodies-from", "skeleton", "--max-frames",
                                     "5", "--matcher", "lomo-xqda"}),
                        2, "--model");
}

// With the shipped models/reid-default.yml.gz, `reid --matcher default` needs no --model, and the
// gallery's scans name that model.
TEST(ReidCli, TheDefaultMatcherUsesTheModelFileWithNoFlag) {
  const auto shipped = find_model_file(kShippedReidModel);
  ASSERT_TRUE(shipped) << kShippedReidModel << " is shipped in models/";
  const std::string id = XqdaEnsemble::load(*shipped).id;
  ASSERT_EQ(id.size(), 8u);
  TempDir dir;
  const fs::path& rec = synth_recording({"--people", "2", "--seed", "3", "--frames", "60", "--scenario", "reenter"});
  const std::string gallery = (dir / "g.db").string();
  const RunResult r = run_bodyrec({"reid", rec.string(), "--matcher", "default", "--gallery", gallery, "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["matcher"], "default");
  EXPECT_EQ(j["users"].get<int>(), 2);
  const RunResult show = run_bodyrec({"gallery", "--gallery", gallery, "show", "1"});
  ASSERT_EQ(show.exit_code, 0) << show.err;
  EXPECT_TRUE(contains(show.out, "default/lomo4-gog1-cs3-xqda-" + id)) << show.out;
}

TEST(EvalReidCli, BadInputGivesOneLineErrorsAndExitCodes) {
  const std::string root = person_set().string();
  auto run = [&](const std::vector<std::string>& args) { return run_bodyrec(args); };
  RunResult r = run({"eval", "reid", "--root", root, "--id-regex", "/p\\d+\\.png$", "--cam-regex", "^cam(\\d)/"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "capture group")) << r.err;
  r = run({"eval", "reid", "--root", root, "--id-regex", "/q(\\d+)\\.png$", "--cam-regex", "^cam(\\d)/"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "no image path matches")) << r.err;
  r = run({"eval", "reid", "--root", root, "--id-regex", "/p(\\d+)\\.png$", "--cam-regex", "^cam(\\d)/",
           "--matcher", "sift"});
  EXPECT_EQ(r.exit_code, 2);
  r = run({"eval", "reid", "--root", root, "--id-regex", "/p(\\d+)\\.png$", "--cam-regex", "^cam(\\d)/",
           "--train-ids", "10"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "leaves no identity to test")) << r.err;
  // Identities each in one camera only.
  TempDir lonely;
  fs::create_directories(lonely / "cam1");
  fs::create_directories(lonely / "cam2");
  cv::imwrite((lonely / "cam1" / "p01.png").string(), person(1, 0));
  cv::imwrite((lonely / "cam2" / "p02.png").string(), person(2, 1));
  r = run({"eval", "reid", "--root", lonely.path().string(), "--id-regex", "/p(\\d+)\\.png$", "--cam-regex",
           "^cam(\\d)/"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "both cameras")) << r.err;
  // An unreadable image is named.
  cv::imwrite((lonely / "cam2" / "p01.png").string(), person(1, 1));
  write_text(lonely / "cam1" / "p02.png", "not a png");
  r = run({"eval", "reid", "--root", lonely.path().string(), "--id-regex", "/p(\\d+)\\.png$", "--cam-regex",
           "^cam(\\d)/", "--train-ids", "0", "--matcher", "lomo"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "p02.png: cannot read the image")) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
}  // namespace bodyrec::testing
