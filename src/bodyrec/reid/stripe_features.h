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

#include <cstdint>
#include <optional>
#include <vector>

#include "bodyrec/reid/descriptor_view.h"
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
std::optional<double> stripe_distance(DescriptorView a, DescriptorView b, const StripeOptions& options = {});

// Stripe descriptors kept for searching: per row only the bands it shows, their non-zero bins and
// squared norms, so comparing a probe with a row costs its non-zero bins instead of every bin (a band's
// histogram fills a few of its 128 bins). distances() gives stripe_distance(probe, row) up to float
// rounding (identical descriptors: ~1e-7, not 0).
class StripeIndex {
 public:
  explicit StripeIndex(StripeOptions options = {});
  size_t size() const { return rows_.size(); }
  // REQUIRES stripe_length(options) floats.
  void push_back(DescriptorView descriptor);
  void set(size_t row, DescriptorView descriptor);
  void swap_remove(size_t row);  // the last row moves into `row`
  // out[i] = stripe_distance(probe, row i); out resized to size().
  void distances(DescriptorView probe, std::vector<std::optional<double>>& out) const;

 private:
  struct Bin {
    uint32_t index;  // within the descriptor
    float value;
  };
  struct Row {
    uint64_t shown = 0;          // bit b: band b has pixels
    std::vector<float> norm;     // per band: squared norm (0 when not shown)
    std::vector<uint32_t> start; // per band: its first bin in `bins` (bands + 1 entries)
    std::vector<Bin> bins;
  };
  Row sparse(DescriptorView descriptor, bool keep_bins = true) const;  // false: bands and norms only
  StripeOptions options_;
  std::vector<Row> rows_;
};

}  // namespace bodyrec
