// People in still photos: the photo preset on the Penn-Fudan test split against OpenCV's own HOG sample
// (docs/benchmarks.md, "People detection on Penn-Fudan photos"), and the whole people it finds on the
// README's photo and another.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/io/pennfudan.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

bool have_dpm_model() { return fs::exists("/usr/share/doc/opencv-doc/examples/dpm/data/inriaperson.xml"); }

TEST(PhotoDetectData, TestSplitAp50OfThePhotoPresetBesideOpenCvsSample) {
  BODYREC_REQUIRE_DATA(root, "pennfudan/PNGImages");
  if (!have_dpm_model()) GTEST_SKIP() << "opencv-doc's inriaperson.xml missing (scripts/install-deps)";
  const std::string dir = root.parent_path().string();
  RunResult r = run_bodyrec({"eval", "detect", "--pennfudan", dir, "--split", "test", "--preset", "photo",
                             "--bootstrap", "2000", "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json photo = last_json_line(r.out);
  EXPECT_EQ(photo["frames"], 42);
  EXPECT_EQ(photo["ground_truth"], 111);
  EXPECT_EQ(photo["detections"], 118);
  EXPECT_NEAR(photo["ap50"].get<double>(), 0.9031, 1e-4);  // the target is 0.80
  EXPECT_NEAR(photo["precision"].get<double>(), 0.8729, 1e-4);
  EXPECT_NEAR(photo["recall"].get<double>(), 0.9279, 1e-4);
  EXPECT_NEAR(photo["ap50_low"].get<double>(), 0.8449, 1e-4);
  EXPECT_NEAR(photo["ap50_high"].get<double>(), 0.9546, 1e-4);
  r = run_bodyrec({"eval", "detect", "--pennfudan", dir, "--split", "test", "--preset", "opencv", "--json", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json opencv = last_json_line(r.out);
  EXPECT_EQ(opencv["ground_truth"], 111);
  EXPECT_NEAR(opencv["ap50"].get<double>(), 0.2777, 1e-4);
}

// Runs `detect IMAGE --preset photo` and counts the people of the image's mask that a detection covers at
// IoU >= 0.5 (each detection covering at most one).
void expect_whole_people(const fs::path& root, const std::string& stem, int people, int detections) {
  const fs::path image = root / "PNGImages" / (stem + ".png");
  const RunResult r = run_bodyrec({"detect", image.string(), "--preset", "photo", "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json row = last_json_line(r.out);
  const std::vector<Box> truth =
      instance_mask_boxes(cv::imread((root / "PedMasks" / (stem + "_mask.png")).string(), cv::IMREAD_GRAYSCALE));
  std::vector<bool> taken(truth.size(), false);
  int found = 0;
  for (const auto& d : row["detections"]) {
    const Box box(d["box"][0].get<double>(), d["box"][1].get<double>(), d["box"][2].get<double>(),
                  d["box"][3].get<double>());
    for (size_t t = 0; t < truth.size(); ++t)
      if (!taken[t] && iou(box, truth[t]) >= 0.5) {
        taken[t] = true;
        ++found;
        break;
      }
  }
  EXPECT_EQ(static_cast<int>(truth.size()), people) << stem;
  EXPECT_EQ(found, people) << stem;
  EXPECT_EQ(static_cast<int>(row["detections"].size()), detections) << stem;
}

TEST(PhotoDetectData, PhotoPresetFindsTheWholePeopleOnNamedPhotos) {
  BODYREC_REQUIRE_DATA(root, "pennfudan/PNGImages");
  if (!have_dpm_model()) GTEST_SKIP() << "opencv-doc's inriaperson.xml missing (scripts/install-deps)";
  expect_whole_people(root.parent_path(), "FudanPed00036", 4, 4);  // the README's example
  expect_whole_people(root.parent_path(), "PennPed00010", 6, 7);  // the seventh box: a person the masks leave out
}

}  // namespace
}  // namespace bodyrec::testing
