// What the re-identification matchers compare: one image of one person, optionally with the body's mask.
#pragma once

#include <opencv2/core/mat.hpp>

namespace bodyrec {

struct PersonImage {
  cv::Mat bgr;   // CV_8UC3, the person's crop (any size; descriptors resample it)
  cv::Mat mask;  // optional CV_8U of bgr's size, 0 = background; empty = every pixel is the person
};

}  // namespace bodyrec
