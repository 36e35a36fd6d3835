// Multi-scale Retinex (Jobson et al. 1997), as LOMO uses it (Liao et al. CVPR 2015) to even out the
// lighting difference between cameras before colour histograms are taken.
#pragma once

#include <opencv2/core/mat.hpp>

namespace bodyrec {

// REQUIRES bgr CV_8UC3; mask empty or CV_8U of bgr's size (0 = background).
// ENSURES a CV_8UC3 image of bgr's size with the same hue and saturation per pixel and a normalised
// brightness: the intensity I (channel mean) goes through MSR, the mean over sigmas {5, 20} of
// log(I + 1) - log(Gauss_sigma * (I + 1)), stretched to 1..255 between its 1st and 99th percentile
// (of the masked pixels, when a mask is given); each colour is scaled by MSR / I, capped at 255
// (chromaticity-preserving Retinex, MSRCP).
cv::Mat multiscale_retinex(const cv::Mat& bgr, const cv::Mat& mask = cv::Mat());

}  // namespace bodyrec
