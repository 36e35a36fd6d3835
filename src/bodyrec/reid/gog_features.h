// GOG, the hierarchical Gaussian descriptor (Matsukawa, Okabe, Suzuki, Sato, CVPR 2016): each small
// patch is summarised by the Gaussian of its pixel features (vertical position, gradient orientation
// magnitudes, colour), each horizontal region by the Gaussian of its patch Gaussians; each Gaussian is
// embedded as a symmetric positive definite matrix and flattened through the matrix logarithm.
#pragma once

#include <vector>

#include "bodyrec/reid/person_image.h"

namespace bodyrec {

enum class GogColour { kRgb, kLab, kHsv, kNrNg };

struct GogOptions {
  int width = 48, height = 128;  // every image is resampled to this size first
  int patch = 5, stride = 2;     // square patches, one every `stride` pixels in both directions
  int regions = 7;               // horizontal regions of height/4, one every height/8
  double epsilon = 1e-3;         // added to both levels' covariance diagonals
  void check() const;            // throws UsageError naming the bad field
};

// Length of one colour space's descriptor: regions x (m + 1)(m + 2)/2 with m = (d + 1)(d + 2)/2 and d the
// pixel feature length (8, or 7 for kNrNg): 7567 (4921 for kNrNg) with the defaults.
int gog_length(GogColour colour, const GogOptions& options = {});

// REQUIRES image.bgr CV_8UC3 non-empty; image.mask empty or CV_8U of the same size.
// Pixel features: [y / height, M_0, M_90, M_180, M_270, colour] where M_theta are the gradient
// magnitude ([-1 0 1] filters on the grey levels in [0, 1]) voted linearly into the two nearest of four
// orientation bins and the colour channels lie in [0, 1]. A patch's Gaussian N(mu, S + eps I) becomes
// |S + eps I|^(-1/(d+1)) [[S + eps I + mu mu^T, mu], [mu^T, 1]]; its matrix logarithm's upper triangle
// (off-diagonals times sqrt 2) is the patch vector. A region's Gaussian is that of its patch vectors
// (those with their centre in the region and at least half body), weighted by exp(-dx^2 / (2 (W/4)^2))
// with dx the patch centre's horizontal distance from the image centre, embedded the same way. With no
// patch in a region its part is zeros. Not normalised (the matchers centre and scale it).
std::vector<float> gog_features(const PersonImage& image, GogColour colour, const GogOptions& options = {});

}  // namespace bodyrec
