// Compact whole-body colour descriptor for online re-identification without a learned model: the
// image (a tight crop of the body) cut into horizontal stripes of equal height, one joint HSV histogram
// of the body's pixels (mask) per stripe at full resolution, normalised and square-rooted (Hellinger), so that the squared Euclidean distance of two descriptors is
// the sum of the stripes' squared Hellinger distances (0..2 each). About 4 KB per scan, where LOMO x 2
// is 216 KB: a gallery of 100 users x 8 views stays under 4 MB in memory.
#pragma once

#include <vector>

#include "bodyrec/reid/person_image.h"

namespace bodyrec {

struct StripeOptions {
  int stripes = 8;
  int hue_bins = 8, sat_bins = 4, val_bins = 4;
  void check() const;  // UsageError naming the bad field
};

// stripes x hue_bins x sat_bins x val_bins (1024 for the defaults).
int stripe_length(const StripeOptions& options = {});

// REQUIRES image.bgr CV_8UC3 non-empty, image.mask empty or CV_8U of the same size.
// ENSURES stripe_length() floats; a stripe with no body pixels is all zeros (it then differs from a
// filled stripe by 1, the Hellinger distance of disjoint histograms, halved).
std::vector<float> stripe_features(const PersonImage& image, const StripeOptions& options = {});

}  // namespace bodyrec
