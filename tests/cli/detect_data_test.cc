// Detection on real footage against real ground truth, and the thesis author's dlib detector.
#include <algorithm>
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bodyrec/eval/detection_metrics.h"
#include "bodyrec/io/ground_truth.h"
#include "test_support.h"

namespace bodyrec::testing {
namespace {

TEST(DetectData, FindsPeopleInFirstFiftyFramesOfVtest) {
  if (!std::filesystem::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  BODYREC_REQUIRE_DATA(gt_path, "pets09_s2l1/PETS2009-S2L1.xml");
  TempDir dir;
  const auto mot = dir / "det.mot";
  const RunResult r = run_bodyrec({"detect", vtest_path().string(), "--max-frames", "50", "--mot", mot.string(),
                                   "--jsonl", (dir / "d.jsonl").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto detections = read_mot(mot.string(), false).by_frame();
  const auto truth = read_cvml(gt_path.string()).by_frame();
  DetectionEvaluator evaluator;
  for (int f = 0; f < 50; ++f) {
    std::vector<Detection> found;
    if (detections.count(f))
      for (const auto& b : detections.at(f)) found.push_back({b.box, b.score});
    evaluator.add_frame(found, truth.count(f) ? truth.at(f) : std::vector<LabelledBox>{});
  }
  const DetectionScores s = evaluator.scores();
  EXPECT_EQ(s.frames, 50);
  EXPECT_GT(s.recall, 0.5);
  EXPECT_GT(s.precision, 0.5);
}

TEST(DetectData, EvalDetectJsonOnFiftyFrames) {
  if (!std::filesystem::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  BODYREC_REQUIRE_DATA(gt_path, "pets09_s2l1/PETS2009-S2L1.xml");
  const RunResult r = run_bodyrec({"eval", "detect", "--source", vtest_path().string(), "--gt", gt_path.string(),
                                   "--max-frames", "50", "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // The last stdout line is the JSON object.
  ASSERT_FALSE(r.out.empty());
  ASSERT_EQ(r.out.back(), '\n');
  const auto start = r.out.rfind('\n', r.out.size() - 2);
  const std::string last = r.out.substr(start == std::string::npos ? 0 : start + 1);
  const auto j = nlohmann::json::parse(last);
  ASSERT_TRUE(j.is_object()) << last;
  for (const char* key : {"ap50", "precision", "recall", "frames", "ms_per_frame"}) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["frames"].get<int>(), 50);
  EXPECT_GT(j["recall"].get<double>(), 0.5);
  EXPECT_GT(j["ms_per_frame"].get<double>(), 0.0);
  EXPECT_GT(j["ap50"].get<double>(), 0.5);
  // The thesis preset at the original size misses most of these small people.
  const RunResult thesis = run_bodyrec({"eval", "detect", "--source", vtest_path().string(), "--gt",
                                        gt_path.string(), "--max-frames", "50", "--preset", "thesis", "--json", "-q"});
  ASSERT_EQ(thesis.exit_code, 0) << thesis.err;
  const auto t = nlohmann::json::parse(thesis.out.substr(thesis.out.rfind('{')));
  EXPECT_LT(t["ap50"].get<double>(), j["ap50"].get<double>());
}

TEST(DetectData, ThesisAuthorsDlibDetectorLoadsAndRuns) {
  if (!std::filesystem::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  BODYREC_REQUIRE_DATA(model, "thesis_ch3/object_detector.svm");
  const RunResult r = run_bodyrec({"detect", vtest_path().string(), "--max-frames", "3", "--model", model.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 3);
  std::istringstream lines(r.out);
  int frame = 0;
  for (std::string line; std::getline(lines, line); ++frame) {
    const auto row = nlohmann::json::parse(line);
    EXPECT_EQ(row["frame"].get<int>(), frame);
    for (const auto& d : row["detections"]) {
      ASSERT_EQ(d["box"].size(), 4u);
      EXPECT_TRUE(d["score"].is_number());
    }
  }
  EXPECT_EQ(frame, 3);
}

TEST(DetectData, NonModelFilesGivenToModelExitThree) {
  if (!std::filesystem::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  BODYREC_REQUIRE_DATA(model, "thesis_ch3/object_detector.svm");
  BODYREC_REQUIRE_DATA(xml, "thesis_ch3/mydataset8.xml");
  auto expect_input_error = [](const RunResult& r, const std::string& path) {
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(path), std::string::npos) << r.err;
  };
  expect_input_error(run_bodyrec({"detect", vtest_path().string(), "--max-frames", "1", "--model", xml.string(), "-q"}),
                     xml.string());
  TempDir dir;
  const std::string text = read_text(model);
  const auto half = dir / "half.svm";
  write_text(half, text.substr(0, text.size() / 2));  // a truncated model
  expect_input_error(run_bodyrec({"detect", vtest_path().string(), "--max-frames", "1", "--model", half.string(), "-q"}),
                     half.string());
  const auto missing = dir / "missing.svm";
  expect_input_error(run_bodyrec({"detect", vtest_path().string(), "--model", missing.string(), "-q"}), missing.string());
}

}  // namespace
}  // namespace bodyrec::testing
