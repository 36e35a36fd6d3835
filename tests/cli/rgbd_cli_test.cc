// `bodyrec synth` and `bodyrec import` as a user meets them: outputs, byte-identical determinism, errors.
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/rgbd/recording.h"

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

// Concatenated bytes of every file of a directory, in name order.
std::string all_bytes(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::string s;
  for (const auto& f : files) s += fs::relative(f, dir).string() + "\n" + read_text(f);
  return s;
}

TEST(SynthCli, SameSeedGivesIdenticalBytesDifferentSeedDiffers) {
  TempDir dir;
  const auto run = [&](const std::string& name, const std::string& seed) {
    const RunResult r = run_bodyrec({"synth", "--people", "2", "--seed", seed, "--frames", "6", "--scenario", "group",
                                     "--out", (dir / name).string(), "--json", "-q"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r;
  };
  const RunResult a = run("a", "11");
  run("b", "11");
  run("c", "12");
  const auto j = last_json_line(a.out);
  EXPECT_EQ(j["frames"].get<int>(), 6);
  EXPECT_EQ(j["people"].get<int>(), 2);
  EXPECT_TRUE(fs::exists(dir / "a" / "color" / "000005.png"));
  EXPECT_TRUE(fs::exists(dir / "a" / "truth" / "000005.json"));
  EXPECT_EQ(all_bytes(dir / "a"), all_bytes(dir / "b"));
  EXPECT_NE(all_bytes(dir / "a"), all_bytes(dir / "c"));
}

TEST(SynthCli, UsageErrors) {
  TempDir dir;
  const RunResult nine = run_bodyrec({"synth", "--people", "9", "--out", (dir / "x").string()});
  EXPECT_EQ(nine.exit_code, 2);
  EXPECT_TRUE(contains(nine.err, "--people")) << nine.err;
  EXPECT_EQ(std::count(nine.err.begin(), nine.err.end(), '\n'), 1) << nine.err;  // one line
  EXPECT_FALSE(fs::exists(dir / "x" / "meta.json"));
  EXPECT_EQ(run_bodyrec({"synth", "--scenario", "dance", "--out", (dir / "x").string()}).exit_code, 2);
  fs::create_directories(dir / "full");
  write_text(dir / "full" / "f.txt", "x");
  const RunResult r = run_bodyrec({"synth", "--frames", "1", "--out", (dir / "full").string(), "-q"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "output exists and is not an empty directory")) << r.err;
}

TEST(ImportCli, BrokenInputsExitWithThreeAndNameTheFile) {
  TempDir dir;
  write_text(dir / "bad.skeleton", "2\n1\n");
  RunResult r = run_bodyrec({"import", "ntu", (dir / "bad.skeleton").string(), "--out", (dir / "o1").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "bad.skeleton: unexpected end of file after line 2")) << r.err;
  write_text(dir / "bad.pcd", "VERSION 0.7\nFIELDS x y z\n");
  r = run_bodyrec({"import", "pcd", (dir / "bad.pcd").string(), "--out", (dir / "o2").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "bad.pcd: no DATA line")) << r.err;
  r = run_bodyrec({"import", "pcd", (dir / "missing.pcd").string(), "--out", (dir / "o3").string()});
  EXPECT_EQ(r.exit_code, 3);
}

TEST(GreenScreenCli, WritesOneCutoutPerVisibleBodyAndRefusesBodiesOnlyRecordings) {
  TempDir dir;
  ASSERT_EQ(run_bodyrec({"synth", "--people", "2", "--seed", "3", "--frames", "60", "--out", (dir / "rec").string(), "-q"})
                .exit_code,
            0);
  const RunResult r = run_bodyrec({"greenscreen", (dir / "rec").string(), "--out", (dir / "cut").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["frames"].get<int>(), 60);
  int bodies = 0;  // one cut-out per body-index slot with pixels, per frame
  for (int i = 0; i < 60; ++i) {
    const auto truth = nlohmann::json::parse(read_text(dir / "rec" / "truth" / (frame_stem(i) + ".json")));
    for (const auto& p : truth["people"]) bodies += p["visible_pixels"].get<int>() > 0 ? 1 : 0;
  }
  EXPECT_EQ(j["cutouts"].get<int>(), bodies);
  EXPECT_GT(bodies, 60);
  const cv::Mat cut = cv::imread((dir / "cut" / "000030_body0.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(cut.type(), CV_8UC4);
  EXPECT_EQ(cut.size(), cv::Size(512, 424));

  write_text(dir / "s.skeleton", "1\n0\n");
  ASSERT_EQ(run_bodyrec({"import", "ntu", (dir / "s.skeleton").string(), "--out", (dir / "ntu").string()}).exit_code, 0);
  const RunResult bad = run_bodyrec({"greenscreen", (dir / "ntu").string(), "--out", (dir / "cut2").string()});
  EXPECT_EQ(bad.exit_code, 3);
  EXPECT_TRUE(contains(bad.err, "greenscreen needs colour and depth streams")) << bad.err;
}

// A sensor or recording without a body index (OpenNI2 sensors give none): bodies from the depth-only
// segmentation, one cut-out per person it finds; --sensor without a device is one line and exit 3.
TEST(GreenScreenCli, WithoutABodyIndexCutsOutSegmentedPeople) {
  TempDir dir;
  ASSERT_EQ(run_bodyrec({"synth", "--people", "1", "--seed", "3", "--frames", "30", "--out", (dir / "rec").string(), "-q"})
                .exit_code,
            0);
  auto meta = nlohmann::json::parse(read_text(dir / "rec" / "meta.json"));
  meta["streams"] = {"color", "depth"};
  write_text(dir / "rec" / "meta.json", meta.dump());
  const RunResult r = run_bodyrec({"greenscreen", (dir / "rec").string(), "--out", (dir / "cut").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["frames"], 30);
  EXPECT_EQ(j["bodies_from"], "segmentation");
  int visible = 0;  // frames where the one person shows enough of themselves to be segmented
  for (int i = 0; i < 30; ++i) {
    const auto truth = nlohmann::json::parse(read_text(dir / "rec" / "truth" / (frame_stem(i) + ".json")));
    visible += truth["people"][0]["visible_fraction"].get<double>() > 0.5 ? 1 : 0;
  }
  EXPECT_GE(j["cutouts"].get<int>(), visible - 2) << r.out;
  EXPECT_LE(j["cutouts"].get<int>(), 30) << r.out;
  const cv::Mat cut = cv::imread((dir / "cut" / "000020_body0.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(cut.type(), CV_8UC4);
  // The person's pixels and only theirs: opaque where the body index says person, mostly.
  const cv::Mat truth = cv::imread((dir / "rec" / "bodyindex" / "000020.png").string(), cv::IMREAD_UNCHANGED);
  std::vector<cv::Mat> channels;
  cv::split(cut, channels);
  const cv::Mat opaque = channels[3] > 0, person = truth != 255;
  const double overlap = cv::countNonZero(opaque & person), union_px = cv::countNonZero(opaque | person);
  EXPECT_GT(overlap / union_px, 0.8);

  const RunResult none = run_bodyrec({"greenscreen", "--sensor", "--out", (dir / "live").string()});
  EXPECT_EQ(none.exit_code, 3);
  EXPECT_EQ(std::count(none.err.begin(), none.err.end(), '\n'), 1) << none.err;
}

}  // namespace
}  // namespace bodyrec::testing
