// `bodyrec eval groups` on the real walking-group scenes: the JSON summary with the plain rule beside the
// default, and the nested leave-one-scene-out table (every figure of docs/benchmarks.md "Walking groups").
#include <map>

#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

TEST(EvalGroupsData, Zara01DefaultAndBaselineJson) {
  BODYREC_REQUIRE_DATA(scene, "walking_groups/UCY/zara01");
  const RunResult r = run_bodyrec({"eval", "groups", "--scene", scene.string(), "--baseline", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  for (const char* key : {"pair_precision", "pair_recall", "pair_f1", "pairs", "baseline"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["pairs"].get<int>(), 849);
  EXPECT_NEAR(j["pair_f1"].get<double>(), 0.9178, 1e-4);
  EXPECT_NEAR(j["baseline"]["pair_f1"].get<double>(), 0.7614, 1e-4);
  EXPECT_TRUE(contains(r.out, "trained on seq_eth seq_hotel")) << r.out;
  const RunResult rule = run_bodyrec({"eval", "groups", "--scene", scene.string(), "--method", "threshold",
                                      "--max-distance", "1.5", "--max-speed-difference", "0.3", "--json"});
  ASSERT_EQ(rule.exit_code, 0) << rule.err;
  EXPECT_NEAR(last_json_line(rule.out)["pair_f1"].get<double>(), 0.8392, 1e-4);
}

// Pair F1 per held-out scene (seq_eth, seq_hotel, zara01) of every family, as --nested prints them.
struct NestedRow {
  const char* method;
  double f1[3];
};

const NestedRow kNested[] = {
    {"plain rule 2.0 m / 0.4 m/s, linkage none", {0.6854, 0.4677, 0.7614}},
    {"plain rule 2.0 m / 0.4 m/s, linkage single", {0.4855, 0.4052, 0.6518}},
    {"plain rule 2.0 m / 0.4 m/s, linkage chosen", {0.6854, 0.4677, 0.6994}},
    {"learned rule, whole common time, linkage none", {0.6081, 0.6383, 0.8613}},
    {"learned rule, whole common time, linkage single", {0.7419, 0.7231, 0.9178}},
    {"learned rule, whole common time, linkage chosen", {0.7419, 0.7231, 0.9178}},
    {"learned rule, windows, linkage none", {0.6360, 0.6619, 0.8346}},
    {"learned rule, windows, linkage single", {0.7516, 0.7705, 0.7952}},
    {"learned rule, windows, linkage chosen", {0.5615, 0.7705, 0.7952}},
    {"pair model, distance + speed difference, linkage none", {0.6109, 0.6870, 0.8235}},
    {"pair model, distance + speed difference, linkage single", {0.6598, 0.9020, 0.8794}},
    {"pair model, distance + speed difference, linkage chosen", {0.5942, 0.9020, 0.8794}},
    {"pair model, all features, linkage none", {0.6273, 0.6715, 0.5686}},
    {"pair model, all features, linkage single", {0.8290, 0.8142, 0.6095}},
    {"pair model, all features, linkage chosen", {0.8290, 0.8142, 0.6095}},
    {"chosen among all of the above", {0.8290, 0.8142, 0.6095}},
};

TEST(EvalGroupsData, NestedLeaveOneSceneOutTable) {
  BODYREC_REQUIRE_DATA(eth, "walking_groups/ETH/seq_eth");
  BODYREC_REQUIRE_DATA(hotel, "walking_groups/ETH/seq_hotel");
  BODYREC_REQUIRE_DATA(zara, "walking_groups/UCY/zara01");
  const RunResult r = run_bodyrec({"eval", "groups", "--nested", "--scene", eth.string(), "--scene", hotel.string(),
                                   "--scene", zara.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  std::map<std::string, nlohmann::json> by_name;
  for (const auto& m : j["methods"]) by_name[m["method"].get<std::string>()] = m;
  ASSERT_EQ(by_name.size(), std::size(kNested));
  for (const auto& row : kNested) {
    const auto& m = by_name.at(row.method);
    double sum = 0;
    for (int s = 0; s < 3; ++s) {
      EXPECT_NEAR(m["scenes"][s]["pair_f1"].get<double>(), row.f1[s], 1e-4) << row.method << " scene " << s;
      sum += row.f1[s];
    }
    EXPECT_NEAR(m["mean_pair_f1"].get<double>(), sum / 3, 2e-4) << row.method;
  }
  const auto& chosen = by_name.at("learned rule, whole common time, linkage chosen")["scenes"];
  EXPECT_EQ(chosen[0]["chosen"].get<std::string>(),
            "learned rule 1.2 m / 0.25 m/s, whole common time, min-moving 0.5, velocity span 0.4 s, linkage single");
  // The default holds better than the plain rule on every scene.
  for (int s = 0; s < 3; ++s) EXPECT_GT(kNested[5].f1[s], kNested[0].f1[s]) << s;
}

}  // namespace
}  // namespace bodyrec::testing
