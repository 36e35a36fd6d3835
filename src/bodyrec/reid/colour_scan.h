// Partial scans of people seen by a plain camera (thesis Ch6 without depth): the colour pixels of a tracked
// person's box that a body mask keeps, with a quality that decides which scan online re-identification
// keeps per user and view (the same PartialScan as from an RGB-D frame, reid/partial_scan.h).
//
// Body masks (BodyMasker): the foreground of a background model inside the box (static camera; the
// default), or another masker, e.g. the program's filled outline of a body shape model (apps/bodyrec/
// shape_body_mask.h). Either way the mask is reduced to its largest part.
//
// Quality in 0..1 = completeness x (0.5 + 0.5 sharpness) x (0.5 + 0.5 resolution), as for RGB-D scans:
//   completeness: 1, times 0.4 when the box touches the image's top or bottom (the stripes descriptor spans
//     the crop from the feet to the head: a cut body would misplace its colours), times 0.6 when it touches
//     a side, times max(0, 1 - 2 x occluded) (the share of the box that other people's boxes cover: their
//     pixels are in its mask), times min(1, fill / 0.35) (a mask filling little of the box is a poor cut);
//   sharpness: variance of the Laplacian inside the (eroded) mask, v / (v + 100);
//   resolution: mask height over half the image height, capped at 1.
// Without depth there are no heights per row: with a stature (from a calibration) the rows get heights
// from the stature at the mask's top down to 0 at its bottom; without, none (the descriptor then takes the
// crop to span the body).
//
//   ForegroundBodyMask masks(detector.model());
//   if (auto s = colour_scan(frame, box, masks.mask(frame, box), view, occluded)) ... s->quality
#pragma once

#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "bodyrec/detection/foreground_detector.h"
#include "bodyrec/reid/partial_scan.h"

namespace bodyrec {

class BodyMasker {
 public:
  virtual ~BodyMasker() = default;
  // The person's mask in `box` of `frame` (BGR; box clipped to it): CV_8U of the clipped box's size, 255 =
  // body; empty when there is none.
  virtual cv::Mat mask(const cv::Mat& frame, const cv::Rect& box) = 0;
  virtual std::string describe() const = 0;
};

// The foreground of a background model inside the box. `model` must outlive this and be updated with
// every frame before mask() is asked for it.
class ForegroundBodyMask : public BodyMasker {
 public:
  explicit ForegroundBodyMask(const ForegroundModel& model) : model_(model) {}
  cv::Mat mask(const cv::Mat& frame, const cv::Rect& box) override;
  std::string describe() const override { return "foreground"; }

 private:
  const ForegroundModel& model_;
};

struct ColourScanOptions {
  int min_pixels = 300;        // fewer mask pixels -> no scan
  int margin_px = 2;           // crop margin around the mask
  double sharpness_ref = 100;  // variance of the Laplacian that counts as half sharp
  void check() const;          // UsageError naming the field
};

// The scan of the person in `box` of `frame` (BGR) with `mask` (box-sized, as BodyMasker gives it).
// `occluded`: the share 0..1 of the box covered by other people's boxes. `stature_m`, when known, gives
// the rows heights. nullopt with `why` set when the mask is empty or too small. InputError when the mask
// does not match the clipped box.
std::optional<PartialScan> colour_scan(const cv::Mat& frame, const cv::Rect& box, const cv::Mat& mask,
                                       const ViewEstimate& view, double occluded,
                                       std::optional<double> stature_m = std::nullopt,
                                       const ColourScanOptions& options = {}, std::string* why = nullptr);

// The largest 8-connected part of a mask (CV_8U, 255 = set); empty input gives empty output.
cv::Mat largest_part(const cv::Mat& mask);

}  // namespace bodyrec
