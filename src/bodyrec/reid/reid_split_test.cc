#include "bodyrec/reid/reid_split.h"

#include <algorithm>
#include <set>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/core/error.h"
#include "test_support.h"

namespace bodyrec {
namespace {

using testing::TempDir;

void write_image(const std::filesystem::path& path) {
  std::filesystem::create_directories(path.parent_path());
  cv::imwrite(path.string(), cv::Mat(16, 8, CV_8UC3, cv::Scalar(10, 20, 30)));
}

// ids 01..05 in both cameras a and b, 06 only in b (distractor), 07 only in a, plus a non-matching file.
void make_set(const TempDir& dir) {
  for (int id = 1; id <= 5; ++id)
    for (const char* cam : {"a", "b"}) write_image(dir / ("cam_" + std::string(cam) + "/0" + std::to_string(id) + ".png"));
  write_image(dir / "cam_b/06.png");
  write_image(dir / "cam_a/07.png");
  write_image(dir / "notes/readme.png");
  testing::write_text(dir / "cam_a/list.txt", "not an image");
}

const char* kId = "/(\\d+)\\.png$";
const char* kCam = "^cam_(\\w)/";

TEST(ReidSplit, ScanReadsIdentityAndCameraFromThePaths) {
  TempDir dir;
  make_set(dir);
  const ReidDataset d = scan_reid_dataset(dir.path().string(), kId, kCam);
  EXPECT_EQ(d.images.size(), 12u);
  EXPECT_EQ(d.skipped, 1);  // notes/readme.png; list.txt is not an image at all
  EXPECT_EQ(d.cameras[0], "a");
  EXPECT_EQ(d.cameras[1], "b");
  EXPECT_EQ(d.identities, (std::vector<std::string>{"01", "02", "03", "04", "05", "06", "07"}));
  EXPECT_EQ(d.in_both, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(d.images[0].path, "cam_a/01.png");
  EXPECT_EQ(d.images[0].camera, 0);
}

TEST(ReidSplit, TrainingIdentitiesAreExcludedAndDistractorsKept) {
  TempDir dir;
  make_set(dir);
  const ReidDataset d = scan_reid_dataset(dir.path().string(), kId, kCam);
  const ReidSplit s = make_reid_split(d, 2, 0, 0);
  std::set<int> train_ids, probe_ids, gallery_ids;
  for (int i : s.train) train_ids.insert(d.images[i].identity);
  for (int i : s.probes) {
    probe_ids.insert(d.images[i].identity);
    EXPECT_EQ(d.images[i].camera, 0);
  }
  for (int i : s.gallery) {
    gallery_ids.insert(d.images[i].identity);
    EXPECT_EQ(d.images[i].camera, 1);
  }
  EXPECT_EQ(train_ids.size(), 2u);
  EXPECT_EQ(s.train.size(), 4u);   // both cameras of each training identity
  EXPECT_EQ(s.probes.size(), 3u);  // the other three identities in both cameras; 07 (camera a only) is not a probe
  EXPECT_EQ(s.gallery.size(), 4u); // their camera-b images + the distractor 06
  EXPECT_TRUE(gallery_ids.count(5));
  EXPECT_FALSE(probe_ids.count(6));
  for (int t : train_ids) EXPECT_FALSE(probe_ids.count(t) || gallery_ids.count(t));
  // Deterministic per (seed, index), different across indices.
  EXPECT_EQ(make_reid_split(d, 2, 0, 0).train, s.train);
  bool differs = false;
  for (int k = 1; k < 6; ++k) differs |= make_reid_split(d, 2, 0, k).train != s.train;
  EXPECT_TRUE(differs);
  // No training: every identity in both cameras is a probe.
  EXPECT_EQ(make_reid_split(d, 0, 0, 0).probes.size(), 5u);
  EXPECT_THROW(make_reid_split(d, 5, 0, 0), UsageError);
}

TEST(ReidSplit, BadRegexesAndDataAreReported) {
  TempDir dir;
  make_set(dir);
  const std::string root = dir.path().string();
  EXPECT_THROW(scan_reid_dataset(root, "\\d+\\.png", kCam), UsageError);  // no capture group
  EXPECT_THROW(scan_reid_dataset(root, "(\\d+", kCam), UsageError);       // does not compile
  EXPECT_TRUE(testing::contains(testing::input_error([&] { scan_reid_dataset(root, "^zzz(\\d)", kCam); }),
                                "no image path matches"));
  EXPECT_TRUE(testing::contains(testing::input_error([&] { scan_reid_dataset(root, kId, "^cam_(a)/"); }),
                                "exactly two"));
  EXPECT_TRUE(testing::contains(testing::input_error([&] { scan_reid_dataset((dir / "missing").string(), kId, kCam); }),
                                "not a folder"));
  // Identities each in one camera only: nothing to test.
  TempDir lonely;
  write_image(lonely / "cam_a/01.png");
  write_image(lonely / "cam_b/02.png");
  EXPECT_TRUE(testing::contains(testing::input_error([&] { scan_reid_dataset(lonely.path().string(), kId, kCam); }),
                                "no identity has images in both cameras"));
}

}  // namespace
}  // namespace bodyrec
