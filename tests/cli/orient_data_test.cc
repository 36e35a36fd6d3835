// `bodyrec orient` on a real Kinect v2 skeleton file (NTU RGB+D, ../shared/datasets/ntu_skeleton).
#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

// A001 "drink water" seen by NTU's camera 1, which sees the performer at 45 degrees: FL in every frame.
TEST(OrientCliData, NtuSkeletonCameraOneIsFrontLeft) {
  BODYREC_REQUIRE_DATA(file, "ntu_skeleton/samples/S001C001P001R001A001.skeleton");
  const RunResult r = run_bodyrec({"orient", file.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["frames"].get<int>(), 103);
  EXPECT_EQ(j["bodies"].get<int>(), 103);
  EXPECT_EQ(j["no_view"].get<int>(), 0);
  EXPECT_EQ(j["views"]["FL"].get<int>(), 103);
  // The thesis rule without a face flag (no colour in the file) gives a reason for every frame it
  // cannot decide.
  const RunResult t = run_bodyrec({"orient", file.string(), "--views", "thesis"});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_TRUE(contains(t.out, "view none: ")) << t.out.substr(0, 400);
}

}  // namespace
}  // namespace bodyrec::testing
