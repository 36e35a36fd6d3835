// The thesis's appearance score (digest Ch6, Listing 6.11): KAZE keypoints and descriptors on both
// images, a FLANN k-d tree on the gallery ("model") image's descriptors, 2 nearest neighbours of each
// probe ("observed") descriptor, kept when best / second distance <= 0.80, and
// score = 2 x (matches kept). score > 10 means the same person.
#pragma once

#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/reid/person_image.h"

namespace bodyrec {

constexpr double kKazeRatio = 0.80;
constexpr double kKazeThreshold = 10.0;

// KAZE descriptors of the image (CV_32F, one 64-float row per keypoint; the mask limits detection).
cv::Mat kaze_descriptors(const PersonImage& image);

// The thesis's score. 0 when either side has fewer than 2 descriptors (no second neighbour).
// Each call uses a fresh knnMatch output: OpenCV 4.6's FlannBasedMatcher::knnMatch appends to the
// vector it is given instead of clearing it.
int kaze_score(const cv::Mat& probe_descriptors, const cv::Mat& gallery_descriptors);

// Descriptors as one float vector (rows, cols, values...) so a gallery can store them as a blob.
std::vector<float> pack_descriptors(const cv::Mat& descriptors);
// Inverse of pack_descriptors; throws InputError when the vector is not one.
cv::Mat unpack_descriptors(const std::vector<float>& packed);

}  // namespace bodyrec
