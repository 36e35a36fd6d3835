// The AP50 that `eval detect` prints must equal what independent AP code computes from the `--mot`
// file of the same run. tests/tools/ap50.py is that code (Python standard library only).
#include <cstdlib>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

TEST(ApCrosscheck, EvalDetectMatchesIndependentCodeOnItsOwnMotOutput) {
  BODYREC_REQUIRE_DATA(gt, "pets09_s2l1/PETS2009-S2L1.xml");
  if (std::system("python3 --version >/dev/null 2>&1") != 0) GTEST_SKIP() << "python3 not installed";
  TempDir dir;
  const auto mot = (dir / "det.mot").string();
  const RunResult r = run_bodyrec({"eval", "detect", "--source", vtest_path().string(), "--gt", gt.string(),
                                   "--max-frames", "120", "--mot", mot, "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto ours = last_json_line(r.out);
  EXPECT_EQ(ours["frames"].get<int>(), 120);

  const std::string script = source_dir() + "/tests/tools/ap50.py";
  const auto out_file = dir / "ref.json";
  const std::string cmd = "python3 '" + script + "' '" + mot + "' '" + gt.string() + "' --frames 120 > '" +
                          out_file.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const auto reference = nlohmann::json::parse(read_text(out_file));
  EXPECT_NEAR(ours["ap50"].get<double>(), reference["coco"].get<double>(), 1e-6);
  EXPECT_NEAR(ours["ap50"].get<double>(), reference["voc"].get<double>(), 1e-6);
  EXPECT_EQ(ours["detections"].get<int>(), reference["detections"].get<int>());
  EXPECT_GT(ours["ap50"].get<double>(), 0.6);
}

}  // namespace
}  // namespace bodyrec::testing
