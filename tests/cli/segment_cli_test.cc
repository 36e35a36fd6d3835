// `bodyrec segment`, `eval segment`, `contour` and `record` as a user meets them: on a short synthetic
// recording generated here, with broken inputs, and `record` without a device.
#include <algorithm>
#include <filesystem>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/rgbd/recording.h"
#include "bodyrec/rgbd/segment.h"

#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec::testing {
namespace {

// 40 frames of 3 people crossing, seed 12 (not one of the seeds 1-3 the segmentation was tuned on).
const fs::path& synth_recording() {
  static TempDir dir;
  static const fs::path rec = [] {
    const fs::path r = dir / "rec";
    const RunResult s = run_bodyrec({"synth", "--people", "3", "--seed", "12", "--frames", "40", "--scenario", "cross",
                                     "--out", r.string(), "-q"});
    EXPECT_EQ(s.exit_code, 0) << s.err;
    return r;
  }();
  return rec;
}

TEST(EvalSegmentCli, DepthOnlyMasksMatchTheBodyIndexOnAnUnseenSeed) {
  const RunResult r = run_bodyrec({"eval", "segment", synth_recording().string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["frames"].get<int>(), 40);
  EXPECT_GE(j["persons"].get<int>(), 60);
  EXPECT_GE(j["mean_iou"].get<double>(), 0.90);
  EXPECT_TRUE(j.contains("ms_per_frame"));
}

TEST(SegmentCli, WritesJsonLinesAndMasks) {
  TempDir dir;
  // Frame 15 of this recording shows all three people (4913, 4391 and 7205 body-index pixels).
  const RunResult r = run_bodyrec({"segment", synth_recording().string(), "--jsonl", (dir / "s.jsonl").string(),
                                   "--masks", (dir / "m").string(), "--max-frames", "16", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = last_json_line(r.out);
  EXPECT_EQ(j["frames"].get<int>(), 16);
  EXPECT_TRUE(j["background"].get<bool>());
  RecordingReader rec(synth_recording().string());
  const RgbdFrame last = rec.read_frame(15);
  int visible = 0;
  for (const auto& p : last.truth->people) visible += p.visible_pixels >= 500;
  EXPECT_EQ(visible, 3);
  EXPECT_EQ(j["people"].get<int>(), 3);
  const std::string lines = read_text(dir / "s.jsonl");
  EXPECT_EQ(std::count(lines.begin(), lines.end(), '\n'), 16);
  const cv::Mat mask = cv::imread((dir / "m" / "000015.png").string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(mask.type(), CV_8U);
  EXPECT_EQ(mask.cols, 512);
  // Each person's mask overlaps its body index well.
  cv::Mat truth = last.body_index.clone();
  truth.setTo(cv::Scalar(kNoBody), last.depth == 0);
  for (double iou : match_masks(truth, mask).iou) EXPECT_GT(iou, 0.8);
}

TEST(ContourCli, LandmarksWithCameraSpacePointsAndAnnotatedImages) {
  TempDir dir;
  for (const std::string method : {"ccd", "opencv"}) {
    const fs::path jsonl = dir / (method + ".jsonl"), images = dir / method;
    const RunResult r = run_bodyrec({"contour", synth_recording().string(), "--landmarks", "24", "--method", method,
                                     "--max-frames", "16", "--jsonl", jsonl.string(), "--annotate", images.string(),
                                     "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(last_json_line(r.out)["labels"].get<std::string>(), "bodyindex");
    EXPECT_EQ(last_json_line(r.out)["frames"].get<int>(), 16);
    EXPECT_EQ(last_json_line(r.out)["bodies"].get<int>(), 3);  // frame 15 shows all three
    std::istringstream in(read_text(jsonl));
    std::string line;
    int bodies = 0;
    while (std::getline(in, line)) {
      const auto frame = nlohmann::json::parse(line);
      for (const auto& b : frame["bodies"]) {
        ++bodies;
        ASSERT_EQ(b["landmarks"].size(), 24u);
        ASSERT_EQ(b["points"].size(), 24u);
        // Point 0 is the top of the outline: no landmark lies higher in the image.
        for (const auto& p : b["landmarks"]) EXPECT_GE(p[1].get<double>(), b["landmarks"][0][1].get<double>());
        ASSERT_FALSE(b["points"][0].is_null());
        EXPECT_GT(b["points"][0][2].get<double>(), 0.5);  // metres in front of the camera
        EXPECT_LT(b["points"][0][2].get<double>(), 6.0);
      }
    }
    EXPECT_GE(bodies, 10);
    EXPECT_TRUE(fs::exists(images / "000015.png"));
  }
}

// A depth-only recording of `frames` frames of a wall 3 m away.
void write_flat_depth_recording(const std::filesystem::path& dir, int frames) {
  RecordingMeta meta;
  meta.sensor = "test";
  meta.depth = meta.color = kinect2_depth_intrinsics();
  meta.streams.depth = true;
  RecordingWriter w(dir.string(), meta);
  RgbdFrame f;
  f.depth = cv::Mat(424, 512, CV_16U, cv::Scalar(3000));
  for (int i = 0; i < frames; ++i) w.write(f);
}

TEST(SegmentCli, BrokenInputsExitWithThreeAndNameTheFile) {
  TempDir dir;
  RunResult r = run_bodyrec({"segment", (dir / "missing").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "missing")) << r.err;
  // A recording whose depth file of frame 1 is corrupt: frame 0's line is still written.
  write_flat_depth_recording(dir / "rec", 2);
  write_text(dir / "rec" / "depth" / "000001.png", "not a png");
  r = run_bodyrec({"segment", (dir / "rec").string(), "--jsonl", (dir / "out.jsonl").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "000001.png")) << r.err;
  EXPECT_TRUE(contains(read_text(dir / "out.jsonl"), "\"frame\":0"));
  // A recording long enough for the background pre-pass (10 frames or more), broken at frame 5: the
  // pre-pass learns from the frames it can read, and frames 0-4 are written before the error.
  write_flat_depth_recording(dir / "long", 12);
  write_text(dir / "long" / "depth" / "000005.png", "not a png");
  r = run_bodyrec({"segment", (dir / "long").string(), "--jsonl", (dir / "long.jsonl").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "000005.png")) << r.err;
  const std::string lines = read_text(dir / "long.jsonl");
  EXPECT_EQ(std::count(lines.begin(), lines.end(), '\n'), 5) << lines;
  // eval segment needs a body index.
  r = run_bodyrec({"eval", "segment", (dir / "rec").string()});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_TRUE(contains(r.err, "needs depth and body index")) << r.err;
  // Usage errors.
  EXPECT_EQ(run_bodyrec({"segment", (dir / "rec").string(), "--background", "sometimes"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"contour", (dir / "rec").string(), "--method", "snake"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"contour", (dir / "rec").string(), "--landmarks", "0"}).exit_code, 2);
  EXPECT_EQ(run_bodyrec({"segment", (dir / "rec").string(), "--min-height", "2", "--max-height", "1.5"}).exit_code, 2);
}

TEST(RecordCli, WithoutADeviceFailsWithOneLineAndExitThree) {
  TempDir dir;
  const RunResult r = run_bodyrec({"record", "--out", (dir / "live").string(), "--frames", "3"});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_TRUE(contains(r.err, "OpenNI2")) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir / "live"));  // nothing half-written
}

}  // namespace
}  // namespace bodyrec::testing
