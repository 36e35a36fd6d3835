#include "bodyrec/reid/face_evidence.h"

#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

// messi5.jpg from Debian's opencv-doc (installed by scripts/install-deps): one player, face at about
// (226, 94) 37x37 px, seen from the front.
const char* kMessi = "/usr/share/doc/opencv-doc/examples/data/messi5.jpg";

TEST(FaceDetector, FindsTheFrontalFaceInTheHeadRegionOnly) {
  if (!std::filesystem::exists(kMessi)) GTEST_SKIP() << kMessi << " missing (opencv-doc)";
  const cv::Mat img = cv::imread(kMessi);
  ASSERT_FALSE(img.empty());
  FaceDetector faces;
  // The head box a skeleton or mask would give: a bit larger than the face.
  const FaceResult head = faces.detect(img, cv::Rect2d(220, 78, 48, 62));
  EXPECT_TRUE(head.looked);
  ASSERT_TRUE(head.face);
  EXPECT_GT((head.box & cv::Rect(226, 94, 37, 37)).area(), 0.5 * 37 * 37);
  // The shirt (below the head) and the ball hold no face.
  const FaceResult shirt = faces.detect(img, cv::Rect2d(215, 150, 50, 62));
  EXPECT_TRUE(shirt.looked);
  EXPECT_FALSE(shirt.face);
  const FaceResult ball = faces.detect(img, cv::Rect2d(337, 288, 50, 50));
  EXPECT_FALSE(ball.face);
  // Too small or outside the image: not looked at.
  EXPECT_FALSE(faces.detect(img, cv::Rect2d(220, 78, 8, 10)).looked);
  EXPECT_FALSE(faces.detect(img, cv::Rect2d(-200, -200, 60, 60)).looked);
  EXPECT_FALSE(faces.detect(cv::Mat(), cv::Rect2d(220, 78, 48, 62)).looked);
}

TEST(FaceDetector, MissingCascadeIsAnInputError) {
  EXPECT_THROW(FaceDetector("/nonexistent/cascade.xml"), InputError);
}

TEST(LargestFace, LargestWinsAndTiesDoNotFollowTheOrder) {
  const cv::Rect small(0, 0, 10, 10), upper(50, 5, 20, 20), lower(5, 40, 20, 20), left(30, 5, 20, 20);
  EXPECT_EQ(largest_face({small, lower, upper}), upper);
  EXPECT_EQ(largest_face({upper, small, lower}), upper);
  EXPECT_EQ(largest_face({upper, left}), left);  // equal size and height: the leftmost
  EXPECT_EQ(largest_face({left, upper}), left);
  EXPECT_EQ(largest_face({small, cv::Rect(0, 90, 11, 11)}), cv::Rect(0, 90, 11, 11));
}

}  // namespace
}  // namespace bodyrec
