// Front/back evidence from a face detector on a body's head region of the colour image (the thesis used
// the Kinect Face API, which we do not have). OpenCV's Haar frontal-face cascade from Debian's
// opencv-data (/usr/share/opencv4/haarcascades/haarcascade_frontalface_alt2.xml), run only on the crop
// around the head, upscaled so that the head is about 64 px tall. (On opencv-doc's messi5.jpg head crop,
// alt2, default and the plain LBP cascade find the face; lbpcascade_frontalface_improved does not.)
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/objdetect.hpp>

namespace bodyrec {

// Where Debian installs the cascade; FaceDetector("") uses it.
std::string default_face_cascade();

struct FaceResult {
  bool looked = false;  // the head region was inside the image and large enough to look at
  bool face = false;    // a frontal face was found in it
  cv::Rect box;         // the face, colour pixels (when face)
};

// The face to keep among several found: the largest; of equal ones the topmost, then the leftmost, so
// that the choice does not follow the order OpenCV's parallel search returns them in. REQUIRES non-empty.
cv::Rect largest_face(const std::vector<cv::Rect>& faces);

class FaceDetector {
 public:
  // Loads the cascade (default_face_cascade() when empty). Throws InputError naming the file when it
  // cannot be loaded.
  explicit FaceDetector(const std::string& cascade_file = "");
  // Looks for a frontal face in `head` (colour pixels, the expected head box). Regions smaller than
  // `min_head_px` tall or mostly outside the image are not looked at (looked = false).
  // REQUIRES color CV_8UC3.
  FaceResult detect(const cv::Mat& color, const cv::Rect2d& head, int min_head_px = 14);

 private:
  cv::CascadeClassifier cascade_;
  cv::Mat grey_;
};

}  // namespace bodyrec
