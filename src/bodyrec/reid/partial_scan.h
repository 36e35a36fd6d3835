// Partial scans (thesis Ch6): the background-removed colour image of one person in one frame, with the
// view it shows and a quality that decides which scan the online pipeline keeps per user and view.
//
// The person's depth pixels (body index slot, or a depth segmentation's label) are mapped into the
// colour image (camera.h: unproject, depth_to_color, project), each splatted over the colour pixels it
// covers, and the mask is closed (holes of depth dropouts) and reduced to its largest part. The scan is
// the colour crop around the mask, background set to black, plus the mask (CV_8U, 255 = person).
//
// Quality in 0..1 = completeness x (0.5 + 0.5 sharpness) x (0.5 + 0.5 resolution):
//   completeness: with a skeleton, the share of the body's tracked joints whose depth pixel (within
//     2 px) belongs to the body and lies inside both images (occluded or clipped joints count against),
//     times 0.5 when the head or both feet are missing and no ground plane is given (without heights a
//     descriptor would place the visible part's colours by image row, wrongly); without one, the body's vertical extent over
//     1.6 m (capped at 1), times 0.6 when the mask touches the image border (clipped), times the share
//     of the body's depth pixels that land inside the colour image (the colour camera sees less than
//     the depth camera at the top and bottom, and a body entering at the side shows only a sliver),
//     halved when the body touches the depth image's left or right border (cut off).
//   sharpness: variance of the Laplacian of the grey crop inside the (eroded) mask, v / (v + 100).
//   resolution: mask height over half the colour image height, capped at 1 (far bodies give small scans).
//
//   PartialScanExtractor scans(meta);
//   const ViewEstimate v = orientation.estimate(frame, ref);
//   if (auto s = scans.extract(frame, ref, v)) keep_if_better(user, *s);   // s->quality
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/reid/orientation_estimator.h"
#include "bodyrec/rgbd/ground_plane.h"
#include "bodyrec/rgbd/recording.h"

namespace bodyrec {

struct PartialScan {
  cv::Mat image;  // CV_8UC3 BGR crop of the colour image; pixels outside the mask are black
  cv::Mat mask;   // CV_8U, image size: 255 person, 0 background
  cv::Rect box;   // the crop in colour pixels
  int pixels = 0;            // mask pixels
  double in_colour = 0;      // share of the body's depth pixels that map inside the colour image,
                             // halved when the body touches the depth image's side
  double completeness = 0;   // 0..1 (see above)
  double sharpness = 0;      // 0..1
  double resolution = 0;     // 0..1
  double quality = 0;        // 0..1
  bool head = false, feet = false;  // head / both feet visible (skeleton), or top/bottom not clipped
  ViewEstimate view;         // as given to extract()
  // With a ground plane: per row of the crop, the median height above the floor (metres) of the depth
  // points splatted into that row's mask pixels; NaN for rows without any. Empty without a plane.
  std::vector<float> row_height_m;
};

struct PartialScanOptions {
  int min_pixels = 400;       // fewer mapped colour pixels -> no scan
  int margin_px = 4;          // crop margin around the mask
  double sharpness_ref = 100;  // variance of the Laplacian that counts as half sharp
};

class PartialScanExtractor {
 public:
  // REQUIRES valid intrinsics in `meta` (checked: InputError).
  explicit PartialScanExtractor(const RecordingMeta& meta, PartialScanOptions options = {});

  // The scan of body `ref` (its pixels in ref.labels == ref.label; ref.body optional). nullopt with
  // `why` set when the frame has no colour or depth, or the body maps to fewer than min_pixels colour
  // pixels. Throws InputError when the images disagree with the meta in type or size. With `ground`
  // (rgbd/ground_plane.h, depth camera space) the scan gets row_height_m.
  std::optional<PartialScan> extract(const RgbdFrame& frame, const BodyRef& ref, const ViewEstimate& view,
                                     std::string* why = nullptr, const GroundPlane* ground = nullptr) const;

  // The person's mask in full colour-image coordinates (CV_8U, 255 person), as extract() builds it
  // before cropping; empty when the body has no pixels.
  // `in_colour`, when given, receives PartialScan::in_colour. With `ground` and `heights`, *heights
  // receives a CV_32F colour-size image of each splatted pixel's height above the plane (NaN elsewhere).
  cv::Mat color_mask(const RgbdFrame& frame, const BodyRef& ref, double* in_colour = nullptr,
                     const GroundPlane* ground = nullptr, cv::Mat* heights = nullptr) const;

 private:
  RecordingMeta meta_;
  PartialScanOptions options_;
  std::vector<float> ray_x_, ray_y_;
};

// Sharpness in 0..1 of a body crop: the Laplacian's variance inside `mask` eroded by an ellipse of `erode_px`
// (the mask edge itself is not texture; the whole mask when under 50 pixels remain), as var / (var + ref).
double mask_sharpness(const cv::Mat& bgr, const cv::Mat& mask, int erode_px, double ref);

}  // namespace bodyrec
