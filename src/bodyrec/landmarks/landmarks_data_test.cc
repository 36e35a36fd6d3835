// Real data: the Penn-Fudan contour set (counts checked against the masks independently) and the thesis
// author's 180-landmark files (thesis_ch3), whose numbering convention the set builder follows.
#include <filesystem>
#include <iostream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "bodyrec/landmarks/contour.h"
#include "bodyrec/landmarks/contour_set.h"
#include "bodyrec/landmarks/landmark_dataset.h"
#include "test_support.h"

namespace fs = std::filesystem;

namespace bodyrec {
namespace {

TEST(LandmarksData, PennFudanContourSetCounts) {
  BODYREC_REQUIRE_DATA(root, "pennfudan");
  // Independent count from the masks: instances, and those under 80 px tall (bounding rows of mask == k).
  int instances = 0, small = 0, touching = 0;
  for (const auto& entry : fs::directory_iterator(root / "PedMasks")) {
    const cv::Mat mask = cv::imread(entry.path().string(), cv::IMREAD_GRAYSCALE);
    double max_value = 0;
    cv::minMaxLoc(mask, nullptr, &max_value);
    for (int k = 1; k <= static_cast<int>(max_value); ++k) {
      const cv::Mat person = mask == k;
      const cv::Rect r = cv::boundingRect(person);
      ++instances;
      small += r.height < 80;
      touching += r.x == 0 || r.y == 0 || r.br().x == mask.cols || r.br().y == mask.rows;
    }
  }
  EXPECT_EQ(instances, 423);  // as PROVENANCE.md states
  EXPECT_EQ(small, 12);
  std::cout << "people touching the image border at all: " << touching << "\n";

  testing::TempDir out;
  ContourSetOptions o;
  o.pennfudan_dir = root.string();
  o.out_dir = out.path().string();
  const ContourSetReport r = build_pennfudan_contour_set(o);
  EXPECT_EQ(r.train_images, 128);
  EXPECT_EQ(r.test_images, 42);
  EXPECT_EQ(r.train_people, 301);
  EXPECT_EQ(r.test_people, 110);
  EXPECT_EQ(r.skipped.count(ContourStatus::kTooSmall) ? r.skipped.at(ContourStatus::kTooSmall) : 0, 12);
  EXPECT_EQ(r.skipped_total(), 12);  // none lies more than 10 % on the border

  const LandmarkDataset test = load_landmark_dataset((out / "test.xml").string());
  ASSERT_EQ(test.images.size(), 42u);
  EXPECT_EQ(fs::path(test.images[0].path).filename(), "FudanPed00004.png");  // sorted index 3
  EXPECT_EQ(test.landmarks, 180);
  EXPECT_EQ(test.people(), 110 + 1);  // plus the one small test person, kept as an ignore box
  for (const auto& image : test.images)
    for (const auto& p : image.people) {
      if (p.ignore) continue;
      EXPECT_GT(signed_area2(p.landmarks), 0) << image.path;  // clockwise
      // point 0 is the top of the outline (integer rounding in the XML aside)
      double top = 1e9;
      for (const auto& q : p.landmarks) top = std::min(top, q.y);
      EXPECT_LE(p.landmarks[0].y, top + 1) << image.path;
    }
}

TEST(LandmarksData, ThesisAuthorsConventionMatchesOurs) {
  BODYREC_REQUIRE_DATA(train_xml, "thesis_ch3/training_with_body_landmarks.xml");
  BODYREC_REQUIRE_DATA(test_xml, "thesis_ch3/testing_with_body_landmarks.xml");
  const LandmarkDataset train = load_landmark_dataset(train_xml.string(), false);  // images are not public
  const LandmarkDataset test = load_landmark_dataset(test_xml.string(), false);
  ASSERT_EQ(train.images.size(), 4u);
  ASSERT_EQ(test.images.size(), 4u);
  EXPECT_EQ(train.landmarks, 180);
  for (size_t i = 0; i < 4; ++i) {
    const auto& points = train.images[i].people.at(0).landmarks;
    const Box& box = train.images[i].people.at(0).box;
    EXPECT_GT(signed_area2(points), 0) << i;  // clockwise in the image, as make-contour-set writes
    double top = 1e9;
    for (const auto& q : points) top = std::min(top, q.y);
    EXPECT_LE(points[0].y, top + 1) << i;  // point 0 at the top of the head
    EXPECT_NEAR(points[0].x, box.x + box.width / 2, box.width / 4) << i;
    // The author's test copies are the images mirrored about x = 319.5 (640 px wide) with every landmark
    // mirrored in place, numbering unchanged: so they run counter-clockwise, and landmark k of a test copy
    // sits on the other side of the body from where a model trained on the originals puts landmark k.
    // mirror_contour (our --flip) gives the same points renumbered clockwise from the head top.
    const auto& flipped = test.images[i].people.at(0).landmarks;
    const auto mirrored = mirror_contour(points, 640);
    double renumbering_px = 0;
    for (size_t k = 0; k < 180; ++k) {
      EXPECT_EQ(flipped[k], cv::Point2d(639 - points[k].x, points[k].y)) << i << " " << k;
      EXPECT_EQ(mirrored[k], flipped[(180 - k) % 180]) << i << " " << k;
      renumbering_px += cv::norm(mirrored[k] - flipped[k]) / 180;
    }
    EXPECT_LT(signed_area2(flipped), 0) << i;
    std::cout << "thesis test image " << i << ": same points, numbered clockwise vs as given: mean "
              << renumbering_px << " px apart\n";
  }
}

}  // namespace
}  // namespace bodyrec
