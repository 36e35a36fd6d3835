// `eval detect --pennfudan` and the photo presets on a small drawn Penn-Fudan-like folder: the JSON it
// prints, and broken folders, masks and options.
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "synthetic_silhouette.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

const char* const kDebianDpmModel = "/usr/share/doc/opencv-doc/examples/dpm/data/inriaperson.xml";

RunResult eval_pennfudan(const fs::path& dir, std::vector<std::string> more = {}) {
  std::vector<std::string> args = {"eval", "detect", "--pennfudan", dir.string(), "-q"};
  args.insert(args.end(), more.begin(), more.end());
  return run_bodyrec(args);
}

TEST(PhotoDetectCli, EvalDetectOnAPennFudanFolderPrintsTheVideoKeys) {
  if (!fs::exists(kDebianDpmModel)) GTEST_SKIP() << "opencv-doc's inriaperson.xml missing (scripts/install-deps)";
  TempDir dir;
  make_pennfudan_like(dir / "pf");
  RunResult r = eval_pennfudan(dir / "pf", {"--preset", "photo", "--json", "--bootstrap", "50"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  nlohmann::json j = last_json_line(r.out);
  for (const char* key : {"ap50", "precision", "recall", "frames", "ms_per_frame", "ap50_low", "ap50_high"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["frames"], 2);        // the test split: P03 and P07
  EXPECT_EQ(j["ground_truth"], 2);  // one person each
  EXPECT_TRUE(contains(r.out, "OpenCV DPM cascade"));
  r = eval_pennfudan(dir / "pf", {"--split", "train", "--preset", "opencv", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = last_json_line(r.out);
  EXPECT_EQ(j["frames"], 6);
  EXPECT_EQ(j["ground_truth"], 9);
  EXPECT_FALSE(j.contains("ap50_low"));  // no --bootstrap
  EXPECT_TRUE(contains(r.out, "OpenCV HOG (default SVM, hit 0, stride 8, padding 0"));
  r = eval_pennfudan(dir / "pf", {"--split", "all", "--preset", "opencv", "--json", "--max-frames", "3"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(last_json_line(r.out)["frames"], 3);
}

TEST(PhotoDetectCli, BrokenPennFudanFoldersExitThreeNamingTheFile) {
  TempDir dir;
  expect_one_line_error(eval_pennfudan(dir / "missing"), 3, "PNGImages");
  const fs::path pf = dir / "pf";
  make_pennfudan_like(pf);

  fs::copy_file(pf / "PedMasks" / "P00_mask.png", pf / "PedMasks" / "Q01_mask.png");  // a mask without its image
  expect_one_line_error(eval_pennfudan(pf), 3, "Q01_mask.png");
  fs::remove(pf / "PedMasks" / "Q01_mask.png");

  fs::rename(pf / "PedMasks" / "P07_mask.png", dir / "P07_mask.png");  // an image without its mask
  expect_one_line_error(eval_pennfudan(pf), 3, "P07_mask.png");
  fs::rename(dir / "P07_mask.png", pf / "PedMasks" / "P07_mask.png");

  write_text(pf / "PedMasks" / "P03_mask.png", "not a png\n");  // an unreadable mask
  expect_one_line_error(eval_pennfudan(pf), 3, "P03_mask.png");
  cv::imwrite((pf / "PedMasks" / "P03_mask.png").string(), cv::Mat(200, 240, CV_8UC3, cv::Scalar::all(1)));
  expect_one_line_error(eval_pennfudan(pf), 3, "P03_mask.png");  // colour, not an instance mask
  cv::imwrite((pf / "PedMasks" / "P03_mask.png").string(), cv::Mat(200, 240, CV_8UC1, cv::Scalar::all(1)));

  // Found when the photo is read (the test split's second, frame 1): frame 0's output is on disk.
  const fs::path jsonl = dir / "d.jsonl";
  cv::imwrite((pf / "PedMasks" / "P07_mask.png").string(), cv::Mat(100, 240, CV_8UC1, cv::Scalar::all(1)));
  expect_one_line_error(eval_pennfudan(pf, {"--preset", "opencv", "--jsonl", jsonl.string()}), 3,
                        "P07_mask.png");  // not its image's size
  auto lines = lines_of(read_text(jsonl));
  ASSERT_GE(lines.size(), 1u);
  EXPECT_EQ(nlohmann::json::parse(lines[0])["frame"], 0);
  cv::imwrite((pf / "PedMasks" / "P07_mask.png").string(), cv::Mat(200, 240, CV_8UC1, cv::Scalar::all(1)));
  write_text(pf / "PNGImages" / "P07.png", "");  // an empty image
  expect_one_line_error(eval_pennfudan(pf, {"--preset", "opencv", "--jsonl", jsonl.string()}), 3, "P07.png");
  lines = lines_of(read_text(jsonl));
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(nlohmann::json::parse(lines[0])["frame"], 0);

  fs::remove_all(pf / "PedMasks");
  expect_one_line_error(eval_pennfudan(pf), 3, "PedMasks");
}

TEST(PhotoDetectCli, OptionsThatDoNotFitExitTwo) {
  TempDir dir;
  make_pennfudan_like(dir / "pf");
  const std::string pf = (dir / "pf").string(), image = (dir / "pf" / "PNGImages" / "P00.png").string();
  EXPECT_EQ(eval_pennfudan(dir / "pf", {"--gt", (dir / "gt.xml").string()}).exit_code, 2);
  EXPECT_EQ(eval_pennfudan(dir / "pf", {"--source", image}).exit_code, 2);
  EXPECT_EQ(eval_pennfudan(dir / "pf", {"--split", "validation"}).exit_code, 2);
  EXPECT_EQ(eval_pennfudan(dir / "pf", {"--bootstrap", "-1"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"eval", "detect", "--source", image, "--split", "test"}).exit_code, 2);  // no --pennfudan
  EXPECT_EQ(run_bodyrec({"eval", "detect"}).exit_code, 2);
  const RunResult r = run_bodyrec({"detect", image, "--preset", "photo", "--win-stride", "8", "-q"});
  expect_one_line_error(r, 2, "--win-stride");
  expect_one_line_error(run_bodyrec({"detect", image, "--preset", "photo", "--motion", "on", "-q"}), 2, "--motion on");
}

TEST(PhotoDetectCli, ABrokenPersonModelInBodyrecModelsExitsThreeNamingIt) {
  TempDir dir;
  make_pennfudan_like(dir / "pf");
  write_text(dir / "inriaperson.xml", "<?xml version=\"1.0\"?>\n<opencv_storage>\n<SBin>8</SBin>\n</opencv_storage>\n");
  const RunResult r = run_bodyrec({"detect", (dir / "pf" / "PNGImages" / "P00.png").string(), "--preset", "photo", "-q"},
                                  {"env", "BODYREC_MODELS=" + dir.path().string()});
  expect_one_line_error(r, 3, (dir / "inriaperson.xml").string());
}

}  // namespace
}  // namespace bodyrec::testing
