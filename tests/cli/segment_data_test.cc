// Depth-only segmentation on real data: PCL's five_people frame (Kinect v1, five pedestrians seen from
// behind in a corridor), imported with `bodyrec import pcd`.
#include <gtest/gtest.h>

#include "test_support.h"

namespace bodyrec::testing {
namespace {

TEST(SegmentData, FivePeopleInThePclFrame) {
  BODYREC_REQUIRE_DATA(pcd, "pcl_people_rgbd/five_people.pcd");
  TempDir dir;
  const std::string rec = (dir / "rec").string();
  ASSERT_EQ(run_bodyrec({"import", "pcd", pcd.string(), "--out", rec}).exit_code, 0);
  const RunResult r = run_bodyrec({"segment", rec, "--jsonl", (dir / "s.jsonl").string(), "--masks",
                                   (dir / "masks").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["people"].get<int>(), 5);
  EXPECT_EQ(j["frames"].get<int>(), 1);
  EXPECT_FALSE(j["background"].get<bool>());  // one frame: ground plane and clusters only
  const auto line = nlohmann::json::parse(read_text(dir / "s.jsonl"));
  ASSERT_EQ(line["people"].size(), 5u);
  for (const auto& p : line["people"]) {
    EXPECT_GT(p["height_m"].get<double>(), 1.5) << p.dump();
    EXPECT_LT(p["height_m"].get<double>(), 2.0) << p.dump();
    EXPECT_GT(p["box"][3].get<int>(), 150) << p.dump();  // whole bodies, not fragments (640x480)
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "masks" / "000000.png"));
  // Contours without a body index use the same segmentation: five outlines of 12 landmarks.
  const RunResult c = run_bodyrec({"contour", rec, "--landmarks", "12", "--method", "opencv", "-q", "--json"});
  ASSERT_EQ(c.exit_code, 0) << c.err;
  EXPECT_EQ(last_json_line(c.out)["bodies"].get<int>(), 5);
  EXPECT_EQ(last_json_line(c.out)["labels"].get<std::string>(), "segment");
}

}  // namespace
}  // namespace bodyrec::testing
