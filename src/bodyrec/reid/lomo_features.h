// LOMO, Local Maximal Occurrence features (Liao, Hu, Zhu, Li, CVPR 2015), as the authors' released
// LOMO.m computes them: joint HSV histograms of the (Retinex) colours and SILTP texture histograms at two
// radii on 10x10 patches every 5 pixels, max-pooled along each horizontal row of patches (a viewpoint
// change that moves a pattern sideways does not change the feature), at three scales.
#pragma once

#include <vector>

#include "bodyrec/reid/person_image.h"

namespace bodyrec {

struct LomoOptions {
  int width = 48, height = 128;  // every image is resampled to this size first (the published 128x48)
  int patch = 10, stride = 5;    // square patches; one row of patches every `stride` pixels
  int scales = 3;                // pyramid levels, each a 2x2 average pooling of the previous
  int hsv_bins = 8;              // joint HSV histogram: hsv_bins^3 bins
  float siltp_tau = 0.3f;        // SILTP scale-invariance tolerance
  bool retinex = true;           // colours after multiscale Retinex (retinex.h); false: as seen
  bool mirror = false;           // average each part with the one of the horizontally mirrored image
  void check() const;            // throws UsageError naming the bad field
};

// Length of each part and of the whole feature (26960 for the defaults: 40 patch rows x (512 + 2 x 81)).
int lomo_colour_length(const LomoOptions& options = {});
int lomo_texture_length(const LomoOptions& options = {});  // one SILTP radius
int lomo_length(const LomoOptions& options = {});

// The parts of LOMO of one image, each log(1 + count) and of unit L2 norm (zeros when no pixel counts).
// colour[0]: joint HSV histograms of the colours as seen, colour[1]: after Retinex (each empty unless
// asked for); siltp[0], siltp[1]: SILTP at radius 3 and 5 (the grey levels as seen). With `mirror`
// every part is the mean of the image's and its mirror image's part, scaled back to unit norm, so an
// image and its mirror image get the same parts (a person seen from the other side).
struct LomoParts {
  std::vector<float> colour[2];
  std::vector<float> siltp[2];
};

// REQUIRES image.bgr CV_8UC3 non-empty; image.mask empty or CV_8U of the same size.
// As LOMO.m: HSV channels quantised to hsv_bins levels each (floor(h * bins), h in [0, 1)), the next
// scale's quantised channels are the floored means over 2x2 pixels; SILTP on the grey levels, the next
// scale's grey levels the 2x2 means. Masked-out pixels (mask 0; at coarser scales, blocks with less than
// half body) are not counted and not pooled into body pixels. The mirror image's histograms come from
// the same codes over the mirrored patch grid (SILTP left/right neighbours swapped): equal to those of
// the flipped image when the width is even at every scale (the default 48: 48, 24, 12).
// `unmirrored` (optional, with mirror): also receives the parts before mirror averaging, at no extra cost.
LomoParts lomo_parts(const PersonImage& image, const LomoOptions& options, bool colours_as_seen,
                     bool colours_retinex, bool mirror, LomoParts* unmirrored = nullptr);

// [HSV histograms (options.retinex colours) | SILTP R=3 | SILTP R=5], options.mirror applied: the
// published LOMO feature.
std::vector<float> lomo_features(const PersonImage& image, const LomoOptions& options = {});

}  // namespace bodyrec
