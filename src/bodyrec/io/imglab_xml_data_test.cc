// The thesis author's dlib imglab files (../shared/datasets/thesis_ch3): the 180-landmark body contour
// annotations and the detector's training set.
#include <gtest/gtest.h>

#include "bodyrec/io/imglab_xml.h"
#include "test_support.h"

namespace bodyrec {
namespace {

TEST(ImglabData, TrainingLandmarks) {
  BODYREC_REQUIRE_DATA(path, "thesis_ch3/training_with_body_landmarks.xml");
  const ImglabDataset d = read_imglab(path.string());
  EXPECT_EQ(d.name, "Training bodies");
  ASSERT_EQ(d.images.size(), 4u);
  const std::vector<std::string> files = {"Snapshot_20141209_24.jpg", "Snapshot_20141209_38.jpg",
                                          "Snapshot_20141209_42.jpg", "Snapshot_20141209_43.jpg"};
  for (size_t i = 0; i < d.images.size(); ++i) {
    const auto& image = d.images[i];
    EXPECT_EQ(image.file, files[i]);
    ASSERT_EQ(image.boxes.size(), 1u) << image.file;
    EXPECT_EQ(image.boxes[0].parts.size(), 180u) << image.file;
    const auto points = ordered_parts(image.boxes[0], image.file);
    EXPECT_EQ(points.size(), 180u) << image.file;
  }
  // Relative names resolve beside the XML file.
  EXPECT_EQ(resolve_image_path(path.string(), d.images[0].file),
            (path.parent_path() / "Snapshot_20141209_24.jpg").lexically_normal().string());
  // Part 00 is at the top of the head: the first box's point 0 is (316, 81), 15 px below the box top.
  const auto first = ordered_parts(d.images[0].boxes[0], "first");
  EXPECT_EQ(first[0], cv::Point2d(316, 81));
  EXPECT_EQ(first[1], cv::Point2d(324, 82));
  EXPECT_EQ(d.images[0].boxes[0].box, Box(237, 66, 173, 368));
  EXPECT_EQ(d.images[1].boxes[0].box, Box(260, 45, 184, 392));
}

TEST(ImglabData, TestingLandmarksAreMirroredCopies) {
  BODYREC_REQUIRE_DATA(path, "thesis_ch3/testing_with_body_landmarks.xml");
  const ImglabDataset d = read_imglab(path.string());
  ASSERT_EQ(d.images.size(), 4u);
  for (const auto& image : d.images) {
    EXPECT_NE(image.file.find("flipped_"), std::string::npos) << image.file;
    ASSERT_EQ(image.boxes.size(), 1u) << image.file;
    EXPECT_EQ(ordered_parts(image.boxes[0], image.file).size(), 180u) << image.file;
  }
}

TEST(ImglabData, DetectorTrainingSet) {
  BODYREC_REQUIRE_DATA(path, "thesis_ch3/mydataset8.xml");
  const ImglabDataset d = read_imglab(path.string());
  EXPECT_EQ(d.name, "imglab dataset");
  ASSERT_EQ(d.images.size(), 26u);  // the 26 webcam images the author's detector was trained on
  int boxes = 0;
  for (const auto& image : d.images) {
    EXPECT_EQ(image.file.rfind("/home/karla/", 0), 0u) << image.file;  // the author's absolute paths
    EXPECT_EQ(resolve_image_path(path.string(), image.file), image.file);
    for (const auto& box : image.boxes) {
      EXPECT_EQ(box.label, "body_detected") << image.file;
      EXPECT_FALSE(box.ignore) << image.file;
      EXPECT_TRUE(box.parts.empty()) << image.file;
      ++boxes;
    }
  }
  EXPECT_EQ(boxes, 26);
  EXPECT_EQ(d.images[0].boxes[0].box, Box(187, 51, 186, 394));
}

}  // namespace
}  // namespace bodyrec
