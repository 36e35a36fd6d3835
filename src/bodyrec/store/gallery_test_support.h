// Scans with known contents for the gallery tests and benchmark.
#pragma once

#include <opencv2/core.hpp>

#include "bodyrec/store/gallery_types.h"

namespace bodyrec::store::testing {

// A `rows` x `cols` random BGR image (seeded: same seed, same pixels) with an elliptic body mask,
// 1 x 64 float features filled with `seed`, the descriptor "test" v1.
inline GalleryScan make_scan(View view, double quality, int seed, int rows = 64, int cols = 32) {
  GalleryScan scan;
  scan.view = view;
  scan.image.create(rows, cols, CV_8UC3);
  cv::RNG rng(static_cast<uint64_t>(seed) * 7919 + 1);
  rng.fill(scan.image, cv::RNG::UNIFORM, 0, 256);
  scan.mask = cv::Mat::zeros(rows, cols, CV_8UC1);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) {
      const double dx = (x - cols / 2.0) / (cols / 2.0), dy = (y - rows / 2.0) / (rows / 2.0);
      if (dx * dx + dy * dy < 0.8) scan.mask.at<uint8_t>(y, x) = 255;
    }
  scan.features = cv::Mat(1, 64, CV_32F, cv::Scalar(static_cast<float>(seed)));
  scan.descriptor = "test";
  scan.descriptor_version = 1;
  scan.quality = quality;
  return scan;
}

}  // namespace bodyrec::store::testing
