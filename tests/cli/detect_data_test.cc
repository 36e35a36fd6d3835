// Detection on real footage against real ground truth, and the thesis author's dlib detector.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bodyrec/eval/detection_metrics.h"
#include "bodyrec/io/ground_truth.h"
#include "test_support.h"

namespace bodyrec::testing {
namespace {

TEST(DetectData, FindsPeopleInFirstFiftyFramesOfVtest) {
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
  BODYREC_REQUIRE_DATA(gt_path, "pets09_s2l1/PETS2009-S2L1.xml");
  const RunResult r = run_bodyrec({"eval", "detect", "--source", vtest_path().string(), "--gt", gt_path.string(),
                                   "--max-frames", "50", "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string last = r.out.substr(r.out.rfind('{'));
  const auto j = nlohmann::json::parse(last);
  for (const char* key : {"ap50", "precision", "recall", "frames", "ms_per_frame"}) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["frames"].get<int>(), 50);
  EXPECT_GT(j["ap50"].get<double>(), 0.5);
  // The thesis preset at the original size misses most of these small people.
  const RunResult thesis = run_bodyrec({"eval", "detect", "--source", vtest_path().string(), "--gt",
                                        gt_path.string(), "--max-frames", "50", "--preset", "thesis", "--json", "-q"});
  ASSERT_EQ(thesis.exit_code, 0) << thesis.err;
  const auto t = nlohmann::json::parse(thesis.out.substr(thesis.out.rfind('{')));
  EXPECT_LT(t["ap50"].get<double>(), j["ap50"].get<double>());
}

TEST(DetectData, ThesisAuthorsDlibDetectorLoadsAndRuns) {
  BODYREC_REQUIRE_DATA(model, "thesis_ch3/object_detector.svm");
  const RunResult r = run_bodyrec({"detect", vtest_path().string(), "--max-frames", "3", "--model", model.string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 3);
}

}  // namespace
}  // namespace bodyrec::testing
