// The Penn-Fudan set builder on a small drawn Penn-Fudan-like folder, its annotation parser and datasets
// loaded back with their images.
#include "bodyrec/landmarks/contour_set.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bodyrec/io/imglab_xml.h"
#include "bodyrec/landmarks/landmark_dataset.h"
#include "synthetic_silhouette.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec {
namespace {

using testing::contains;
using testing::input_error;

TEST(ContourSet, BuildsSplitCountsAndFlips) {
  testing::TempDir dir;
  testing::make_pennfudan_like(dir / "pf");
  ContourSetOptions o;
  o.pennfudan_dir = (dir / "pf").string();
  o.out_dir = (dir / "out").string();
  o.contour.landmarks = 30;
  o.flip = true;
  const ContourSetReport r = build_pennfudan_contour_set(o);
  EXPECT_EQ(r.train_images, 6);
  EXPECT_EQ(r.test_images, 2);
  EXPECT_EQ(r.train_people, 6);
  EXPECT_EQ(r.test_people, 2);
  EXPECT_EQ(r.flipped_people, 6);
  EXPECT_EQ(r.skipped.at(ContourStatus::kTooSmall), 2);
  EXPECT_EQ(r.skipped.at(ContourStatus::kTouchesBorder), 1);
  EXPECT_EQ(r.skipped_total(), 3);

  const std::string train_xml = (dir / "out" / "train.xml").string();
  const LandmarkDataset train = load_landmark_dataset(train_xml);
  ASSERT_EQ(train.images.size(), 12u);  // 6 originals, each followed by its mirror
  EXPECT_EQ(train.landmarks, 30);
  EXPECT_EQ(train.people(), 12 + 6);  // 12 with landmarks; ignore boxes: P01, P05 small, P02 border, and mirrors
  EXPECT_EQ(fs::path(train.images[0].path).filename(), "P00.png");
  EXPECT_EQ(fs::path(train.images[1].path).filename(), "P00_flip.png");
  const AnnotatedPerson& a = train.images[0].people[0];
  const AnnotatedPerson& b = train.images[1].people[0];
  EXPECT_EQ(b.box, mirror_box(a.box, 240));
  EXPECT_EQ(b.landmarks[0], cv::Point2d(239 - a.landmarks[0].x, a.landmarks[0].y));
  EXPECT_EQ(b.landmarks[1], cv::Point2d(239 - a.landmarks[29].x, a.landmarks[29].y));
  EXPECT_GT(signed_area2(b.landmarks), 0);
  EXPECT_TRUE(train.images[2].people[1].ignore);  // the small person in P01
  EXPECT_TRUE(train.images[2].people[1].landmarks.empty());
  cv::Mat flipped;
  cv::flip(train.images[0].image, flipped, 1);
  EXPECT_EQ(cv::norm(flipped, train.images[1].image, cv::NORM_INF), 0);

  const LandmarkDataset test = load_landmark_dataset((dir / "out" / "test.xml").string());
  ASSERT_EQ(test.images.size(), 2u);
  EXPECT_EQ(fs::path(test.images[0].path).filename(), "P03.png");
  EXPECT_EQ(fs::path(test.images[1].path).filename(), "P07.png");
}

TEST(ContourSet, BoxMarginGrowsAndClips) {
  EXPECT_EQ(grow_box(Box(10, 20, 40, 100), 0.1, cv::Size(200, 200)), Box(6, 10, 48, 120));
  EXPECT_EQ(grow_box(Box(2, 20, 40, 100), 0.1, cv::Size(200, 200)), Box(0, 10, 46, 120));
  EXPECT_EQ(mirror_box(Box(10, 20, 40, 100), 200), Box(150, 20, 40, 100));
  EXPECT_EQ(mirror_box(mirror_box(Box(10, 20, 40, 100), 200), 200), Box(10, 20, 40, 100));
}

TEST(ContourSet, PennFudanAnnotationParser) {
  testing::TempDir dir;
  testing::write_text(dir / "a.txt",
                      "Image size (X x Y x C) : 559 x 536 x 3\r\n"
                      "Bounding box for object 1 \"PASpersonWalking\" (Xmin, Ymin) - (Xmax, Ymax) : (160, 182) - (302, 431)\r\n"
                      "Bounding box for object 2 \"PASpersonWalking\" (Xmin, Ymin) - (Xmax, Ymax) : (420, 171) - (535, 486)\r\n");
  const auto boxes = read_pennfudan_boxes((dir / "a.txt").string());
  ASSERT_EQ(boxes.size(), 2u);
  EXPECT_EQ(boxes[0], Box(159, 181, 143, 250));

  testing::write_text(dir / "b.txt", "x\nBounding box for object 1 \"P\" (Xmin, Ymin) - (Xmax, Ymax) : (160, 182) - (302)\n");
  EXPECT_TRUE(contains(input_error([&] { read_pennfudan_boxes((dir / "b.txt").string()); }), "b.txt:2"));
  testing::write_text(dir / "c.txt", "Bounding box for object 2 \"P\" (Xmin, Ymin) - (Xmax, Ymax) : (1, 1) - (5, 5)\n");
  EXPECT_TRUE(contains(input_error([&] { read_pennfudan_boxes((dir / "c.txt").string()); }), "out of order"));
  testing::write_text(dir / "d.txt", "Bounding box for object 1 \"P\" (Xmin, Ymin) - (Xmax, Ymax) : (9, 1) - (5, 5)\n");
  EXPECT_TRUE(contains(input_error([&] { read_pennfudan_boxes((dir / "d.txt").string()); }), "d.txt:1"));
  EXPECT_TRUE(contains(input_error([&] { read_pennfudan_boxes((dir / "none.txt").string()); }), "none.txt"));
}

TEST(ContourSet, MissingInputsNameTheFile) {
  testing::TempDir dir;
  ContourSetOptions o;
  o.pennfudan_dir = (dir / "pf").string();
  o.out_dir = (dir / "out").string();
  EXPECT_TRUE(contains(input_error([&] { build_pennfudan_contour_set(o); }), "PNGImages"));
  testing::make_pennfudan_like(dir / "pf");
  fs::remove(dir / "pf" / "PedMasks" / "P02_mask.png");
  EXPECT_TRUE(contains(input_error([&] { build_pennfudan_contour_set(o); }), "P02_mask.png"));
  o.box_margin = -1;
  EXPECT_THROW(build_pennfudan_contour_set(o), UsageError);
}

TEST(LandmarkDataset, BrokenXmlMissingImagesAndMixedLandmarkCounts) {
  testing::TempDir dir;
  cv::imwrite((dir / "a.png").string(), cv::Mat(20, 20, CV_8UC3, cv::Scalar::all(0)));
  testing::write_text(dir / "broken.xml", "<dataset><images><image file='a.png'><box top='1'");
  EXPECT_TRUE(contains(input_error([&] { load_landmark_dataset((dir / "broken.xml").string()); }), "broken.xml"));
  testing::write_text(dir / "missing.xml",
                      "<dataset><images><image file='a.png'/><image file='gone.png'/></images></dataset>");
  const std::string missing = input_error([&] { load_landmark_dataset((dir / "missing.xml").string()); });
  EXPECT_TRUE(contains(missing, "missing.xml")) << missing;
  EXPECT_TRUE(contains(missing, "gone.png")) << missing;
  EXPECT_EQ(load_landmark_dataset((dir / "missing.xml").string(), false).images.size(), 2u);
  testing::write_text(dir / "mixed.xml",
                      "<dataset><images><image file='a.png'>"
                      "<box top='1' left='1' width='5' height='5'><part name='00' x='1' y='1'/><part name='01' x='2' y='2'/></box>"
                      "<box top='1' left='1' width='5' height='5'><part name='00' x='1' y='1'/></box>"
                      "</image></images></dataset>");
  const std::string mixed = input_error([&] { load_landmark_dataset((dir / "mixed.xml").string()); });
  EXPECT_TRUE(contains(mixed, "box 1")) << mixed;
  testing::write_text(dir / "gap.xml",
                      "<dataset><images><image file='a.png'>"
                      "<box top='1' left='1' width='5' height='5'><part name='00' x='1' y='1'/><part name='02' x='2' y='2'/></box>"
                      "</image></images></dataset>");
  EXPECT_TRUE(contains(input_error([&] { load_landmark_dataset((dir / "gap.xml").string()); }), "landmark 1 is missing"));
}

}  // namespace
}  // namespace bodyrec
