// `bodyrec eval groups` on a real scene: the JSON summary the issue asks for.
#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

TEST(EvalGroupsData, Zara01LeaveOneSceneOutJson) {
  BODYREC_REQUIRE_DATA(scene, "walking_groups/UCY/zara01");
  const RunResult r = run_bodyrec({"eval", "groups", "--scene", scene.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  for (const char* key : {"pair_precision", "pair_recall", "pair_f1", "pairs"}) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["pairs"].get<int>(), 849);
  EXPECT_NEAR(j["pair_f1"].get<double>(), 0.9185, 1e-4);
  EXPECT_TRUE(contains(r.out, "trained on seq_eth seq_hotel")) << r.out;
  const RunResult baseline = run_bodyrec({"eval", "groups", "--scene", scene.string(), "--method", "threshold",
                                          "--max-distance", "1.5", "--max-speed-difference", "0.3", "--json"});
  ASSERT_EQ(baseline.exit_code, 0) << baseline.err;
  EXPECT_NEAR(last_json_line(baseline.out)["pair_f1"].get<double>(), 0.8392, 1e-4);
}

}  // namespace
}  // namespace bodyrec::testing
