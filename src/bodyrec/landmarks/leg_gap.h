// A slit for the gap between the legs that the mask network cannot resolve. On its 24x72 grid a gap a
// few image pixels wide (legs close together, or the top of an inverted V) is less than one cell: the
// logits dip along it but stay above the threshold, so the mask's outline runs straight across the feet
// while the true outline goes up between the legs and down again, and every landmark after the feet
// slides. cut_leg_gap follows the valley of lowest logits up from the bottom of the mask and cuts a
// one-pixel slit along it as far as the logits stay below `slit_logit`; the outline then goes up the
// slit and back (Penn-Fudan validation: docs/benchmarks.md, "A slit between the legs").
#pragma once

#include <opencv2/core/mat.hpp>

namespace bodyrec {

// Logits above the mask's threshold that still count as the valley between the legs (chosen on the
// Penn-Fudan validation people, docs/benchmarks.md).
inline constexpr double kLegSlitMargin = 1.0;

// Cuts the slit into `mask` (CV_8UC1, non-zero = body), in place. `logits` (CV_32FC1, the mask's size)
// are what the mask was thresholded from. The valley is the path of least summed logit from the mask's
// middle row to its lowest row with room for it, moving at most one column per row and staying strictly
// between the leftmost and rightmost body pixels of each row (so it never runs down the outside of the
// body). The slit is the part of it, from the bottom up, whose logits are all below `slit_logit`,
// continued straight down to the mask's bottom edge; it is 4-connected background, so an 8-connected
// outline cannot cross it. Nothing is cut when the valley's lowest pixel is not below `slit_logit`.
// Returns the number of rows cut (0 = none).
int cut_leg_gap(cv::Mat& mask, const cv::Mat& logits, double slit_logit);

}  // namespace bodyrec
