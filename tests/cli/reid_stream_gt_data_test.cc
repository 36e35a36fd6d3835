// Plain-camera re-identification on real footage: vtest.avi (PETS 2009 S2L1) scored against its ground
// truth (19 people as the file numbers them). Measured with the defaults (foreground detector, stripes):
// accuracy 0.5615, 17 splits, 6 merges, 36 users; the bounds leave room for small changes, not for a
// collapse. The file gives a person who walks out and comes back a new id, so merges are an upper bound.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

TEST(ReidStreamGtData, PlainCameraReidOnPets2009) {
  BODYREC_REQUIRE_DATA(gt, "pets09_s2l1/PETS2009-S2L1.xml");
  if (!std::filesystem::exists(vtest_path())) GTEST_SKIP() << "vtest.avi missing (opencv-doc)";
  const RunResult r = run_bodyrec({"eval", "reid-stream", vtest_path().string(), "--gt", gt.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = last_json_line(r.out);
  EXPECT_EQ(s["frames"].get<int>(), 795);
  EXPECT_EQ(s["identities"].get<int>(), 19);
  EXPECT_GE(s["accuracy"].get<double>(), 0.50);
  EXPECT_LE(s["splits"].get<int>(), 22);
  EXPECT_LE(s["merges"].get<int>(), 9);
  EXPECT_GE(s["coverage"].get<double>(), 0.65);
}

}  // namespace
}  // namespace bodyrec::testing
