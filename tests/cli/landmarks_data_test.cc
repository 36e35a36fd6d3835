// The landmarking commands on real files: the thesis author's release (thesis_ch3: annotation files whose
// images are not public, and the author's fHOG detector) and Penn-Fudan images.
#include <filesystem>

#include <gtest/gtest.h>

#include "synthetic_silhouette.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

// A small 180-landmark model trained on drawn people (enough to run the commands, not to be accurate).
fs::path tiny_180_landmark_model(const TempDir& dir) {
  make_pennfudan_like(dir / "pf");
  const RunResult set = run_bodyrec({"make-contour-set", "--pennfudan", (dir / "pf").string(), "--out",
                                     (dir / "set").string(), "--landmarks", "180"});
  EXPECT_EQ(set.exit_code, 0) << set.err;
  const RunResult shape = run_bodyrec({"train-shape", (dir / "set" / "train.xml").string(), "--out",
                                       (dir / "shape.dat").string(), "--method", "trees", "--cascade-depth", "2",
                                       "--trees-per-level", "10", "--oversampling", "2"});
  EXPECT_EQ(shape.exit_code, 0) << shape.err;
  return dir / "shape.dat";
}

TEST(LandmarksCliData, ThesisAnnotationsLoadButTheirImagesAreNotPublic) {
  BODYREC_REQUIRE_DATA(xml, "thesis_ch3/testing_with_body_landmarks.xml");
  TempDir dir;
  const fs::path model = tiny_180_landmark_model(dir);
  // The XML parses (180 landmarks match the model); the first image it names is missing: exit 3 naming it.
  const RunResult r = run_bodyrec({"eval", "landmarks", xml.string(), "--shape", model.string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "testing_with_body_landmarks.xml")) << r.err;
  EXPECT_TRUE(contains(r.err, "flipped_")) << r.err;
  EXPECT_TRUE(contains(r.err, "cannot read image")) << r.err;

  BODYREC_REQUIRE_DATA(detector_xml, "thesis_ch3/mydataset8.xml");
  const RunResult d = run_bodyrec({"train-detector", detector_xml.string(), "--out", (dir / "d.svm").string()});
  EXPECT_EQ(d.exit_code, 3);
  EXPECT_TRUE(contains(d.err, "/home/karla/")) << d.err;
}

TEST(LandmarksCliData, AuthorsDetectorAndOursOnPennFudanImages) {
  BODYREC_REQUIRE_DATA(svm, "thesis_ch3/object_detector.svm");
  BODYREC_REQUIRE_DATA(image, "pennfudan/PNGImages/PennPed00010.png");
  TempDir dir;
  const fs::path model = tiny_180_landmark_model(dir);
  for (const std::vector<std::string>& detector :
       {std::vector<std::string>{"--detector", svm.string()}, std::vector<std::string>{"--motion", "off"}}) {
    std::vector<std::string> args = {"landmark", image.string(), "--shape", model.string(), "-q", "--annotate",
                                     (dir / "annotated").string()};
    args.insert(args.end(), detector.begin(), detector.end());
    const RunResult r = run_bodyrec(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto row = last_json_line(r.out);
    EXPECT_EQ(row["frame"], 0);
    for (const auto& p : row["people"]) EXPECT_EQ(p["landmarks"].size(), 180u);
    // The author's detector (trained on 26 frontal webcam images, 640x480) finds none of the six people
    // in this street scene; the HOG detector finds people (and some false positives).
    if (detector[0] == "--detector") EXPECT_EQ(row["people"].size(), 0u);
    else EXPECT_GE(row["people"].size(), 1u);
    EXPECT_TRUE(fs::exists(dir / "annotated" / "000000.png"));
  }
}

}  // namespace
}  // namespace bodyrec::testing
