// LOMO, Local Maximal Occurrence features (Liao, Hu, Zhu, Li, CVPR 2015): colour and texture histograms
// on overlapping patches, max-pooled along each horizontal row so that a viewpoint change that moves a
// pattern sideways does not change the feature.
#pragma once

#include <vector>

#include "bodyrec/reid/person_image.h"

namespace bodyrec {

struct LomoOptions {
  int width = 48, height = 128;  // every image is resampled to this size first
  int patch = 10, stride = 5;    // square patches; one row of patches every `stride` pixels
  int scales = 3;                // pyramid levels, each a 2x2 average pooling of the previous
  int hsv_bins = 8;              // joint HSV histogram: hsv_bins^3 bins
  float siltp_tau = 0.3f;        // SILTP scale-invariance tolerance
  bool retinex = true;           // multi-scale Retinex before the colour histograms
  bool lab = false;              // joint histograms of CIE Lab instead of HSV
  bool mirror = false;           // average with the feature of the horizontally mirrored image
  void check() const;            // throws UsageError naming the bad field
};

// Length of the feature for these options (26960 for the defaults: 40 patch rows x (512 + 2 x 81)).
int lomo_length(const LomoOptions& options = {});

// REQUIRES image.bgr CV_8UC3 non-empty; image.mask empty or CV_8U of the same size.
// ENSURES lomo_length(options) floats: [HSV histograms | SILTP(R=3) | SILTP(R=5)] per patch row and
// scale, each count log(1 + x), the colour part and the texture part each of unit L2 norm. Masked-out
// pixels are not counted (a fully masked image gives zeros).
// With options.mirror: the mean of that feature and the one of the image mirrored left to right, each
// part scaled back to unit norm, so an image and its mirror image give the same feature (a person seen
// from the other side, a viewpoint change). The mirror image's histograms come from the same colour and
// texture codes over the mirrored patch grid, with the SILTP left/right neighbours swapped (about half
// as much time again, not twice): equal to lomo_features of the flipped image, up to float rounding, when
// the resampled width is even at every scale (the default 48: 48, 24, 12).
std::vector<float> lomo_features(const PersonImage& image, const LomoOptions& options = {});

}  // namespace bodyrec
