// Soft biometrics that an RGB-D sensor gives for free: the body's stature (top of its depth points above
// the floor). Colour descriptors cannot tell apart two people who dress alike; their statures usually
// differ by more than the few centimetres a depth sensor's measurement wanders, so online
// re-identification (online_reid.h) fuses a stature term with the appearance score.
//
// One measurement per body and frame: the k-th highest of the body's depth points above the ground
// plane (rgbd/ground_plane.h; points far from the body's median depth are edge pixels, not the body),
// refused when the top cannot be the person's top: the head (the body's points within head_band_m of
// its top) reaches the depth image's border (the top may be outside, e.g. someone entering at the side),
// or a nearer surface (someone or something in front) lies next to it. A track's stature is the upper
// quartile of its measurements (StatureTrack): the head bobs by several centimetres over a stride, and
// people are tallest at mid-stance; single bad frames do not move it.
//
//   if (auto s = measure_stature(frame.depth, meta.depth_unit_m, meta.depth, labels, label, ground)) ...
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/rgbd/camera.h"
#include "bodyrec/rgbd/ground_plane.h"

namespace bodyrec {

struct StatureOptions {
  int top_rank = 5;            // the top is the 5th highest body point (a few flying pixels go)
  double near_body_m = 0.5;    // body pixels farther than this from its median depth are edge noise
  double occluder_m = 0.15;    // a surface this much nearer than the body just above its top hides it
  int above_px = 4;            // pixels around the head checked for such a surface (and the border margin)
  double head_band_m = 0.25;   // the head: body points within this of the top
  double min_m = 0.9, max_m = 2.4;  // plausible statures; others are no measurement
  void check() const;          // UsageError naming the field
};

// The stature of body `label` in `labels` (CV_8U, depth size) from `depth` (CV_16U, depth units of
// `depth_unit_m`), or nullopt with `why` set (too few pixels, top clipped or hidden, implausible).
// REQUIRES depth and labels of the intrinsics' size (InputError otherwise).
std::optional<double> measure_stature(const cv::Mat& depth, double depth_unit_m, const Intrinsics& depth_k,
                                      const cv::Mat& labels, int label, const GroundPlane& ground,
                                      const StatureOptions& options = {}, std::string* why = nullptr);

// A track's measurements: the upper quartile (75th percentile) of the last `keep` ones once `min_count`
// are in.
class StatureTrack {
 public:
  explicit StatureTrack(int min_count = 1, int keep = 150) : min_count_(min_count), keep_(keep) {}
  void add(double stature_m);
  // Over all kept measurements, or only the last `last` of them (what the body looks like now).
  std::optional<double> estimate(int last = 0) const;
  int count() const { return count_; }  // measurements added so far (all, not only those kept)

 private:
  int min_count_, keep_, count_ = 0;
  std::vector<double> values_;  // the last `keep_`, oldest first
};

}  // namespace bodyrec
