// What the re-identification matchers compare: one image of one person, optionally with the body's mask.
#pragma once

#include <vector>

#include <opencv2/core/mat.hpp>

namespace bodyrec {

struct PersonImage {
  cv::Mat bgr;   // CV_8UC3, the person's crop (any size; descriptors resample it)
  cv::Mat mask;  // optional CV_8U of bgr's size, 0 = background; empty = every pixel is the person
  // Optional, one per row of bgr: the height above the floor (metres) of that row's body pixels, as an
  // RGB-D sensor measures it (PartialScan::row_height_m); NaN where unknown, empty when not measured.
  std::vector<float> row_height_m = {};
};

}  // namespace bodyrec
