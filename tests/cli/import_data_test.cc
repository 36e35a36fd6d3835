// `bodyrec import ntu` on a real Kinect v2 skeleton file (NTU RGB+D, ../shared/datasets/ntu_skeleton).
#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

// A055 (two people, "hugging"): 66 frames, two bodies.
TEST(ImportCliData, NtuSampleGivesJsonSummary) {
  BODYREC_REQUIRE_DATA(file, "ntu_skeleton/samples/S017C003P020R002A055.skeleton");
  TempDir dir;
  const RunResult r = run_bodyrec({"import", "ntu", file.string(), "--out", (dir / "rec").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["frames"].get<int>(), 66);
  EXPECT_EQ(j["bodies"].get<int>(), 2);
}

}  // namespace
}  // namespace bodyrec::testing
