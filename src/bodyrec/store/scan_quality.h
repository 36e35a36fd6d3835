// The default quality of a partial scan, which decides whether a new scan replaces the stored one of
// the same user and view (Gallery::put_scan keeps the higher).
#pragma once

#include <opencv2/core/mat.hpp>

namespace bodyrec {

struct ScanQuality {
  double sharpness = 0;     // [0, 1): v / (v + 100), v = variance of the Laplacian over the body
  double completeness = 0;  // [0, 1]: 1 - 0.25 per image edge the body touches (cut off by the frame),
                            // times min(1, body pixels / 2000) (a far or occluded body is incomplete)
  double score = 0;         // sharpness * completeness
};

// REQUIRES: image 8-bit grey or BGR, non-empty; mask empty (the whole image is the body) or 8-bit of
// the image's size. ENSURES: every field in [0, 1]; 0 for an empty mask.
ScanQuality scan_quality(const cv::Mat& image, const cv::Mat& mask);

}  // namespace bodyrec
