// Compact whole-body colour descriptor for online re-identification without a learned model: the
// body's pixels (mask) cut into horizontal bands by their height above the floor, one joint HSV
// histogram per band at full resolution, normalised and square-rooted (Hellinger), so that the squared
// Euclidean distance of two bands is their squared Hellinger distance (0..1).
//
// Bands by height in metres (0-0.2 m, 0.2-0.4 m, ...) rather than by image row: a body half hidden
// behind someone, or cut by the colour image's border, keeps its visible bands where they belong, and
// two scans are compared over the bands both show (stripe_distance). Heights come from the RGB-D scan
// (PersonImage::row_height_m); an image without them (a plain photo) spans 0..assumed_stature_m, top row
// at the top. About 5.5 KB per scan: a gallery of 100 users x 8 views stays under 5 MB in memory.
#pragma once

#include <optional>
#include <vector>

#include "bodyrec/reid/person_image.h"

namespace bodyrec {

struct StripeOptions {
  int bands = 11;                   // bands of band_m from the floor up (11 x 0.2 m = 2.2 m)
  double band_m = 0.2;
  double assumed_stature_m = 1.75;  // rows without a measured height: the crop spans 0..this
  double min_band_share = 0.02;     // a band holding less than this share of the body's pixels stays empty
  int hue_bins = 8, sat_bins = 4, val_bins = 4;
  int min_common = 4;               // stripe_distance needs this many bands shown by both scans
  double compared_bands = 8;        // distances are scaled to this many bands (0..8, as 8 stripes)
  void check() const;  // UsageError naming the bad field
};

// bands x hue_bins x sat_bins x val_bins (1408 for the defaults).
int stripe_length(const StripeOptions& options = {});

// REQUIRES image.bgr CV_8UC3 non-empty, image.mask empty or CV_8U of the same size, row_height_m empty
// or one value per row.
// ENSURES stripe_length() floats; a band with (too few) body pixels is all zeros, one with pixels has
// squared norm 1/2.
std::vector<float> stripe_features(const PersonImage& image, const StripeOptions& options = {});

// Sum of the squared Hellinger distances of the bands both descriptors show, times
// compared_bands / (bands compared): 0 (alike) .. compared_bands (disjoint colours). nullopt when they
// share fewer than min_common bands. REQUIRES both of stripe_length(options).
std::optional<double> stripe_distance(const std::vector<float>& a, const std::vector<float>& b,
                                      const StripeOptions& options = {});

}  // namespace bodyrec
