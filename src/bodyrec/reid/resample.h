// Resampling a person image to a fixed size, as every descriptor and `eval reid --resize` do it.
#pragma once

#include <opencv2/core/mat.hpp>

namespace bodyrec {

// REQUIRES image non-empty, size positive. Area averaging when no side grows (no aliasing when
// shrinking), bilinear interpolation when a side grows (OpenCV's area mode then acts like nearest
// neighbour). Returns the image itself (shared) when it already has that size.
cv::Mat resample_image(const cv::Mat& image, cv::Size size);

// Nearest neighbour, for masks and label images: no new values.
cv::Mat resample_mask(const cv::Mat& mask, cv::Size size);

}  // namespace bodyrec
