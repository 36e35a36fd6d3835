// The shipped models (models/README.md): each is found without a flag and scores its documented figure, and
// its documented commands, run again on ../shared/datasets, make a model that scores within the stated
// tolerance of it.
#include <filesystem>

#include <gtest/gtest.h>

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

// models/README.md: the shipped body shape model's mean error on the Penn-Fudan test split, in box heights.
constexpr double kShippedShapeError = 0.05985;

TEST(ShippedShapeModel, IsFoundWithoutAFlagAndScoresItsFigure) {
  BODYREC_REQUIRE_DATA(pennfudan, "pennfudan");
  TempDir dir;
  const RunResult set = run_bodyrec({"make-contour-set", "--pennfudan", pennfudan.string(), "--out",
                                     (dir / "set").string(), "--flip"});
  ASSERT_EQ(set.exit_code, 0) << set.err;
  const RunResult eval = run_bodyrec({"eval", "landmarks", (dir / "set" / "test.xml").string(), "--json"});
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  const nlohmann::json j = last_json_line(eval.out);
  EXPECT_EQ(j["persons"], 110);
  // The same file on any CPU: fitting's kernels move the figure by far less than a hundredth of a point.
  EXPECT_NEAR(j["mean_rel_height"].get<double>(), kShippedShapeError, 0.0005);
}

TEST(ShippedShapeModel, LandmarkPlacesTheLandmarksOnAPhotoWithNoFlag) {
  BODYREC_REQUIRE_DATA(photo, "pennfudan/PNGImages/FudanPed00036.png");
  TempDir dir;
  const RunResult r = run_bodyrec({"landmark", photo.string(), "--jsonl", (dir / "l.jsonl").string(), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(lines_of(read_text(dir / "l.jsonl")).at(0));
  // The photo detector (--preset auto on a still image) finds its four walkers; each gets 180 landmarks.
  ASSERT_EQ(j["people"].size(), 4u);
  for (const auto& person : j["people"]) EXPECT_EQ(person["landmarks"].size(), 180u);
}

// Runs the documented training (minutes: 5-14 on 2 cores) and checks the model it makes.
TEST(ShippedShapeModel, RetrainingReproducesItsFigure) {
  BODYREC_REQUIRE_DATA(pennfudan, "pennfudan");
  TempDir dir;
  const RunResult set = run_bodyrec({"make-contour-set", "--pennfudan", pennfudan.string(), "--out",
                                     (dir / "set").string(), "--flip"});
  ASSERT_EQ(set.exit_code, 0) << set.err;
  const fs::path model = dir / "body-shape.dat";
  const RunResult train = run_bodyrec({"train-shape", (dir / "set" / "train.xml").string(), "--out", model.string()});
  ASSERT_EQ(train.exit_code, 0) << train.err;
  const RunResult eval = run_bodyrec(
      {"eval", "landmarks", (dir / "set" / "test.xml").string(), "--shape", model.string(), "--json"});
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  // The same instruction set gives the same file; another one's rounding another model, 6.14 % with AVX2
  // kernels: within 0.3 points either way.
  EXPECT_NEAR(last_json_line(eval.out)["mean_rel_height"].get<double>(), kShippedShapeError, 0.003);
}

}  // namespace
}  // namespace bodyrec::testing
