// The landmarking commands end to end on a drawn Penn-Fudan-like folder: make-contour-set, train-shape,
// train-detector, eval landmarks, landmark; and their errors with exit codes.
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>

#include "synthetic_silhouette.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

class LandmarkCommands : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    make_pennfudan_like(*dir_ / "pf");
    set_ = run_bodyrec({"make-contour-set", "--pennfudan", (*dir_ / "pf").string(), "--out", (*dir_ / "set").string(),
                        "--landmarks", "30", "--flip", "--json"});
    shape_ = run_bodyrec({"train-shape", (*dir_ / "set" / "train.xml").string(), "--out", (*dir_ / "shape.dat").string(),
                          "--method", "trees", "--cascade-depth", "4", "--trees-per-level", "30", "--oversampling", "5", "--holdout-every",
                          "3", "--holdout-xml", (*dir_ / "val.xml").string(), "--json"});
  }
  static void TearDownTestSuite() { delete dir_; }
  static fs::path path(const std::string& name) { return *dir_ / name; }

  static TempDir* dir_;
  static RunResult set_, shape_;
};
TempDir* LandmarkCommands::dir_ = nullptr;
RunResult LandmarkCommands::set_, LandmarkCommands::shape_;

TEST_F(LandmarkCommands, MakeContourSetReportsCountsPerReason) {
  ASSERT_EQ(set_.exit_code, 0) << set_.err;
  const auto j = last_json_line(set_.out);
  EXPECT_EQ(j["train_images"], 6);
  EXPECT_EQ(j["test_images"], 2);
  EXPECT_EQ(j["train_people"], 6);
  EXPECT_EQ(j["test_people"], 2);
  EXPECT_EQ(j["flipped_people"], 6);
  EXPECT_EQ(j["skipped_small"], 2);
  EXPECT_EQ(j["skipped_border"], 1);
  EXPECT_TRUE(contains(set_.out, "1 touching the border"));
  EXPECT_TRUE(fs::exists(path("set/images/P00_flip.png")));
}

TEST_F(LandmarkCommands, TrainShapeAndEvalLandmarks) {
  ASSERT_EQ(shape_.exit_code, 0) << shape_.err;
  const auto t = last_json_line(shape_.out);
  EXPECT_EQ(t["train"]["persons"], 8);       // P00, P01, P04, P05 and their mirrors
  EXPECT_EQ(t["validation"]["persons"], 4);  // source images 2 and 5 (P02, P06) with their mirrors
  EXPECT_LT(t["train"]["mean_px"].get<double>(), 20.0);
  EXPECT_GT(t["model_bytes"].get<int>(), 1000);
  // --holdout-xml wrote the validation part: scoring it again gives the same figures.
  const RunResult v = run_bodyrec({"eval", "landmarks", path("val.xml").string(), "--shape", path("shape.dat").string(),
                                   "--json"});
  ASSERT_EQ(v.exit_code, 0) << v.err;
  EXPECT_EQ(last_json_line(v.out)["persons"], 4);
  EXPECT_NEAR(last_json_line(v.out)["mean_px"].get<double>(), t["validation"]["mean_px"].get<double>(), 1e-9);

  const RunResult e = run_bodyrec({"eval", "landmarks", path("set/test.xml").string(), "--shape",
                                   path("shape.dat").string(), "--json"});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const auto j = last_json_line(e.out);
  for (const char* key : {"mean_px", "mean_rel_height", "mean_rel_width", "p90_rel_height", "persons", "ms_per_person",
                          "point_to_contour_rel_height"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["persons"], 2);
  EXPECT_NEAR(j["mean_rel_width"].get<double>(), j["mean_px"].get<double>() / 240, 1e-5 * j["mean_rel_width"].get<double>());  // JSON: 6 significant digits
  EXPECT_LT(j["mean_px"].get<double>(), 25.0);  // people are 150 px tall
  EXPECT_LE(j["point_to_contour_px"].get<double>(), j["mean_px"].get<double>());

  // --per-person: one JSON line per scored person whose mean is the summary's.
  const RunResult p = run_bodyrec({"eval", "landmarks", path("set/test.xml").string(), "--shape",
                                   path("shape.dat").string(), "--per-person", path("errors.jsonl").string()});
  ASSERT_EQ(p.exit_code, 0) << p.err;
  std::istringstream lines(read_text(path("errors.jsonl")));
  std::string line;
  double sum_px = 0, sum_rel = 0;
  int persons = 0;
  while (std::getline(lines, line)) {
    const auto row = nlohmann::json::parse(line);
    EXPECT_EQ(row["person"], persons);
    EXPECT_TRUE(contains(row["image"].get<std::string>(), "images"));
    sum_px += row["mean_px"].get<double>();
    sum_rel += row["rel_height"].get<double>();
    ++persons;
  }
  EXPECT_EQ(persons, 2);
  EXPECT_NEAR(sum_px / persons, j["mean_px"].get<double>(), 1e-5 * j["mean_px"].get<double>());  // each rounded to 6 digits
  EXPECT_NEAR(sum_rel / persons, j["mean_rel_height"].get<double>(), 1e-5 * j["mean_rel_height"].get<double>());
}

// The default method: the body mask network (a short run, on the same drawn people).
TEST_F(LandmarkCommands, TrainMaskNetThenLandmark) {
  const RunResult t = run_bodyrec({"train-shape", path("set/train.xml").string(), "--out", path("net.dat").string(),
                                   "--iterations", "80", "--net-size", "24x64", "--batch", "8", "--json"});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  const auto j = last_json_line(t.out);
  EXPECT_EQ(j["method"], "mask-net");
  EXPECT_EQ(j["train"]["persons"], 12);  // 6 people and their mirrors
  EXPECT_LT(j["model_bytes"].get<int>(), 1000000);  // ~53 000 weights
  const RunResult e = run_bodyrec({"eval", "landmarks", path("set/test.xml").string(), "--shape",
                                   path("net.dat").string(), "--json"});
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_EQ(last_json_line(e.out)["persons"], 2);
  EXPECT_LT(last_json_line(e.out)["mean_px"].get<double>(), 40.0);  // 150 px people after 80 mini-batches
  const RunResult alone = run_bodyrec({"eval", "landmarks", path("set/test.xml").string(), "--shape",
                                       path("net.dat").string(), "--no-mirror", "--json"});
  ASSERT_EQ(alone.exit_code, 0) << alone.err;
  EXPECT_EQ(last_json_line(alone.out)["persons"], 2);
  const RunResult uncorrected = run_bodyrec({"eval", "landmarks", path("set/test.xml").string(), "--shape",
                                             path("net.dat").string(), "--no-correction", "--json"});
  ASSERT_EQ(uncorrected.exit_code, 0) << uncorrected.err;
  EXPECT_NE(last_json_line(uncorrected.out)["mean_px"], last_json_line(e.out)["mean_px"]);
  const RunResult unslit = run_bodyrec({"eval", "landmarks", path("set/test.xml").string(), "--shape",
                                        path("net.dat").string(), "--no-leg-slit", "--json"});
  ASSERT_EQ(unslit.exit_code, 0) << unslit.err;
  EXPECT_EQ(last_json_line(unslit.out)["persons"], 2);
  // The commands that read a shape model take either kind.
  const RunResult r = run_bodyrec({"landmark", path("set/images/P03.png").string(), "--shape", path("net.dat").string(),
                                   "--motion", "off", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Kept in a variable: a range-for over last_json_line(...)["people"] walks a destroyed temporary (ASan).
  const auto landmarked = last_json_line(r.out);
  for (const auto& p : landmarked["people"]) EXPECT_EQ(p["landmarks"].size(), 30u);
}

TEST_F(LandmarkCommands, TrainDetectorThenLandmarkImages) {
  ASSERT_EQ(shape_.exit_code, 0) << shape_.err;
  const RunResult d = run_bodyrec({"train-detector", path("set/train.xml").string(), "--test",
                                   path("set/test.xml").string(), "--out", path("det.svm").string(), "--target-size",
                                   "60", "--json"});
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const auto dj = last_json_line(d.out);
  EXPECT_GE(dj["train_recall"].get<double>(), 0.5);
  EXPECT_TRUE(dj.contains("test_precision"));

  const RunResult r = run_bodyrec({"landmark", path("set/images/P00.png").string(), "--shape", path("shape.dat").string(),
                                   "--detector", path("det.svm").string(), "--annotate", path("annotated").string(),
                                   "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto row = last_json_line(r.out);
  EXPECT_EQ(row["frame"], 0);
  ASSERT_GE(row["people"].size(), 1u);
  for (const auto& p : row["people"]) {
    EXPECT_EQ(p["box"].size(), 4u);
    EXPECT_TRUE(p["score"].is_number());
    ASSERT_EQ(p["landmarks"].size(), 30u);
    EXPECT_EQ(p["landmarks"][0].size(), 2u);
  }
  EXPECT_TRUE(fs::exists(path("annotated/000000.png")));

  // With a mask-net model, the fast fit (the box alone, one outline) places other landmarks on the same people.
  const RunResult t = run_bodyrec({"train-shape", path("set/train.xml").string(), "--out", path("fastnet.dat").string(),
                                   "--iterations", "40", "--net-size", "24x64", "--batch", "8", "--networks", "1"});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  std::vector<nlohmann::json> rows;
  for (const bool fast : {false, true}) {
    std::vector<std::string> args = {"landmark", path("set/images/P00.png").string(), "--shape",
                                     path("fastnet.dat").string(), "--detector", path("det.svm").string(), "-q"};
    if (fast) args.insert(args.end(), {"--no-mirror", "--threshold-offsets", "0"});
    const RunResult f = run_bodyrec(args);
    ASSERT_EQ(f.exit_code, 0) << f.err;
    rows.push_back(last_json_line(f.out));
  }
  ASSERT_EQ(rows[1]["people"].size(), row["people"].size());
  for (size_t i = 0; i < row["people"].size(); ++i) {
    EXPECT_EQ(rows[1]["people"][i]["box"], rows[0]["people"][i]["box"]);
    ASSERT_EQ(rows[1]["people"][i]["landmarks"].size(), 30u);
    EXPECT_NE(rows[1]["people"][i]["landmarks"], rows[0]["people"][i]["landmarks"]);
  }
}

// After TrainDetectorThenLandmarkImages (its detector): --track gives each person an id that holds across
// frames, fits the shape in the track's box, and writes the tracks as MOT rows.
TEST_F(LandmarkCommands, TrackGivesIdsAcrossFrames) {
  ASSERT_TRUE(fs::exists(path("det.svm")));
  fs::create_directories(path("frames"));
  for (int i = 0; i < 6; ++i)  // the same image six times: one person standing still
    fs::copy_file(path("set/images/P00.png"), path("frames/f" + std::to_string(i) + ".png"));
  const std::vector<std::string> common = {"landmark", path("frames").string(), "--shape", path("shape.dat").string(),
                                           "--detector", path("det.svm").string(), "-q"};
  std::vector<std::string> args = common;
  args.insert(args.end(), {"--track", "--min-score", "0", "--new-track-score", "0", "--mot", path("mot.txt").string()});
  const RunResult r = run_bodyrec(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RunResult plain = run_bodyrec(common);
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const std::vector<std::string> rows = lines_of(r.out), plain_rows = lines_of(plain.out);
  ASSERT_EQ(rows.size(), 6u);
  ASSERT_EQ(plain_rows.size(), 6u);
  const auto first = nlohmann::json::parse(plain_rows[0])["people"];
  ASSERT_EQ(first.size(), 1u);
  // Tentative on frames 0 and 1 (not reported), confirmed with id 1 from the third detection on.
  for (int f = 0; f < 6; ++f) {
    const auto row = nlohmann::json::parse(rows[static_cast<size_t>(f)]);
    EXPECT_EQ(row["frame"], f);
    const auto people = row["people"];
    ASSERT_EQ(people.size(), f < 2 ? 0u : 1u) << "frame " << f;
    if (f < 2) continue;
    EXPECT_EQ(people[0]["id"], 1);
    EXPECT_EQ(people[0]["state"], "confirmed");
    EXPECT_FALSE(people[0].contains("score"));
    EXPECT_EQ(people[0]["landmarks"].size(), 30u);
    for (size_t k = 0; k < 4; ++k)  // the filtered box of a still person: where the detector puts it
      EXPECT_NEAR(people[0]["box"][k].get<double>(), first[0]["box"][k].get<double>(), 3.0) << "frame " << f;
  }
  const std::vector<std::string> mot = lines_of(read_text(path("mot.txt")));
  ASSERT_EQ(mot.size(), 4u);  // frames 2-5, 1-based in MOT
  EXPECT_EQ(mot[0].substr(0, 4), "3,1,");
  EXPECT_EQ(mot[3].substr(0, 4), "6,1,");
}

// On video, landmark --track follows the people `track` follows: the same ids, states and boxes, frame by frame.
TEST_F(LandmarkCommands, TrackFollowsWhomTheTrackCommandFollows) {
  if (!fs::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  const std::vector<std::string> source = {vtest_path().string(), "--max-frames", "20", "-q"};
  std::vector<std::string> args = {"landmark"};
  args.insert(args.end(), source.begin(), source.end());
  args.insert(args.end(), {"--shape", path("shape.dat").string(), "--track"});
  const RunResult landmarked = run_bodyrec(args);
  ASSERT_EQ(landmarked.exit_code, 0) << landmarked.err;
  args = {"track"};
  args.insert(args.end(), source.begin(), source.end());
  const RunResult tracked = run_bodyrec(args);
  ASSERT_EQ(tracked.exit_code, 0) << tracked.err;
  const std::vector<std::string> a = lines_of(landmarked.out), b = lines_of(tracked.out);
  ASSERT_EQ(a.size(), 20u);
  ASSERT_EQ(b.size(), 20u);
  size_t people = 0;
  for (size_t f = 0; f < a.size(); ++f) {
    const auto mine = nlohmann::json::parse(a[f])["people"], theirs = nlohmann::json::parse(b[f])["tracks"];
    ASSERT_EQ(mine.size(), theirs.size()) << "frame " << f;
    for (size_t i = 0; i < mine.size(); ++i) {
      EXPECT_EQ(mine[i]["id"], theirs[i]["id"]) << "frame " << f;
      EXPECT_EQ(mine[i]["state"], theirs[i]["state"]) << "frame " << f;
      EXPECT_EQ(mine[i]["box"], theirs[i]["box"]) << "frame " << f;
      EXPECT_EQ(mine[i]["landmarks"].size(), mine[i]["state"] == "lost" ? 0u : 30u) << "frame " << f;
    }
    people += mine.size();
  }
  EXPECT_GT(people, 20u);  // several people confirmed within 20 frames of vtest.avi
}

TEST_F(LandmarkCommands, ErrorsNameTheFileAndExitWithTheirCode) {
  ASSERT_EQ(shape_.exit_code, 0) << shape_.err;
  const std::string shape = path("shape.dat").string();
  // Broken XML, missing image, no landmarks, a model with another landmark count: input errors (3).
  write_text(path("broken.xml"), "<dataset><images><image file='x.png'>");
  RunResult r = run_bodyrec({"eval", "landmarks", path("broken.xml").string(), "--shape", shape});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "broken.xml")) << r.err;
  write_text(path("gone.xml"), "<dataset><images><image file='set/images/gone.png'/></images></dataset>");
  r = run_bodyrec({"eval", "landmarks", path("gone.xml").string(), "--shape", shape});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "gone.png")) << r.err;
  write_text(path("boxes.xml"), "<dataset><images><image file='set/images/P00.png'>"
                                "<box top='1' left='1' width='50' height='90'/></image></images></dataset>");
  r = run_bodyrec({"train-shape", path("boxes.xml").string(), "--out", path("x.dat").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "no box has landmarks")) << r.err;
  write_text(path("three.xml"), "<dataset><images><image file='set/images/P00.png'><box top='1' left='1' width='50' "
                                "height='90'><part name='0' x='3' y='3'/><part name='1' x='9' y='3'/>"
                                "<part name='2' x='9' y='9'/></box></image></images></dataset>");
  r = run_bodyrec({"eval", "landmarks", path("three.xml").string(), "--shape", shape});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "3 landmarks per box, the model 30")) << r.err;
  r = run_bodyrec({"eval", "landmarks", path("set/test.xml").string(), "--shape", path("set/train.xml").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "neither a dlib shape predictor nor a bodyrec mask-net model")) << r.err;
  r = run_bodyrec({"make-contour-set", "--pennfudan", path("nowhere").string(), "--out", path("o").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "nowhere")) << r.err;
  r = run_bodyrec({"train-detector", path("gone.xml").string(), "--out", path("d.svm").string()});
  EXPECT_EQ(r.exit_code, 3);
  // Usage errors (2).
  r = run_bodyrec({"make-contour-set", "--pennfudan", path("pf").string(), "--out", path("o").string(), "--box-margin",
                   "-0.5"});
  EXPECT_EQ(r.exit_code, 2);
  r = run_bodyrec({"train-shape", path("set/train.xml").string(), "--out", path("x.dat").string(), "--method", "trees",
                   "--nu", "0"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--nu")) << r.err;
  // Options of the other method would be ignored: refused, naming the option.
  r = run_bodyrec({"train-shape", path("set/train.xml").string(), "--out", path("x.dat").string(), "--method", "trees",
                   "--net-size", "32x96"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "bodyrec: error: --net-size is a mask-net option; --method trees takes none\n");
  r = run_bodyrec({"train-shape", path("set/train.xml").string(), "--out", path("x.dat").string(), "--tree-depth", "3"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "bodyrec: error: --tree-depth is a trees option; --method mask-net takes none\n");
  EXPECT_FALSE(fs::exists(path("x.dat")));
  r = run_bodyrec({"train-shape", path("set/train.xml").string(), "--out", path("x.dat").string(), "--net-size", "30x90"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--net-size")) << r.err;
  r = run_bodyrec({"train-shape", path("set/train.xml").string(), "--out", path("x.dat").string(), "--net-size", "32"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--net-size must be WxH")) << r.err;
  r = run_bodyrec({"train-shape", path("set/train.xml").string(), "--out", path("x.dat").string(), "--seed", "abc"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--seed")) << r.err;
  r = run_bodyrec({"train-shape", path("set/train.xml").string(), "--out", path("x.dat").string(), "--method", "svm"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--method")) << r.err;
  r = run_bodyrec({"landmark", path("set/images/P00.png").string(), "--shape", shape, "--mot", path("m.txt").string()});
  EXPECT_EQ(r.exit_code, 2);
  r = run_bodyrec({"eval", "landmarks", path("set/test.xml").string(), "--shape", shape, "--mask-threshold", "0"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "mask-net models only")) << r.err;
  r = run_bodyrec({"eval", "landmarks", path("set/test.xml").string(), "--shape", shape, "--threshold-offsets", "0,1"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--threshold-offsets applies to mask-net models only")) << r.err;
  r = run_bodyrec({"eval", "landmarks", path("set/test.xml").string(), "--shape", shape, "--no-mirror"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--no-mirror applies to mask-net models only")) << r.err;
  r = run_bodyrec({"eval", "landmarks", path("set/test.xml").string(), "--shape", shape, "--no-correction"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--no-correction applies to mask-net models only")) << r.err;
  r = run_bodyrec({"eval", "landmarks", path("set/test.xml").string(), "--shape", shape, "--no-leg-slit"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--no-leg-slit applies to mask-net models only")) << r.err;
  r = run_bodyrec({"landmark", path("set/images/P00.png").string(), "--shape", shape, "--no-mirror"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--no-mirror applies to mask-net models only")) << r.err;
  // MOT rows need ids, and tracker options need the tracker: usage errors (2).
  r = run_bodyrec({"landmark", path("set/images/P00.png").string(), "--shape", shape, "--mot", path("m.txt").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--track")) << r.err;
  r = run_bodyrec({"landmark", path("set/images/P00.png").string(), "--shape", shape, "--min-hits", "2"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--min-hits requires --track")) << r.err;
  r = run_bodyrec({"landmark", path("set/images/P00.png").string(), "--shape", shape, "--track", "--min-hits", "0"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--min-hits must be >= 1")) << r.err;
  r = run_bodyrec({"train-shape", path("set/train.xml").string(), "--out", path("x.dat").string(), "--holdout-xml",
                   path("v.xml").string()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--holdout-every")) << r.err;
  // An output that cannot be written: processing error (4).
  r = run_bodyrec({"train-shape", path("set/train.xml").string(), "--out", path("no/such/dir/x.dat").string(),
                   "--method", "trees", "--cascade-depth", "1", "--trees-per-level", "2"});
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_TRUE(contains(r.err, "x.dat")) << r.err;
}

}  // namespace
}  // namespace bodyrec::testing
