// The robust orientation estimator (`--views robust`, the default) and the thesis rule behind one
// interface, per body and frame, with state per track.
//
// Robust: the body's axis comes from the skeleton (shoulder and hip lines, skeleton_yaw_deg) or, without
// a skeleton, from depth alone (principal axis of the horizontal torso points of the body's pixels, which
// gives the axis up to 180 degrees). Which way the body faces is then decided between the two candidates
// yaw and yaw + 180 by evidence: the skeleton's own left/right (when it has one), a frontal face in the
// head region of the colour image, and the walking direction (people walk forwards), accumulated over
// the track's frames (continuity; capped so that consistent contrary evidence turns it round). The yaw
// is smoothed by an alpha-beta filter on the circle (no lag on a steady turn); the view is the nearest
// 45-degree sector (orientation.h) with a confidence 0..1 from the axis quality, the accumulated evidence
// and the distance to the sector border.
//
//   OrientationEstimator est(reader.meta());
//   for (RgbdFrame f; reader.read(f);)
//     for (const Body& b : f.bodies) {
//       const ViewEstimate v = est.estimate(f, BodyRef::of(b, f.body_index));
//       // v.view (nullopt: v.reason), v.yaw_deg, v.confidence
//     }
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "bodyrec/reid/face_evidence.h"
#include "bodyrec/reid/orientation.h"
#include "bodyrec/rgbd/recording.h"

namespace bodyrec {

enum class ViewMethod { kRobust, kThesis };
// "robust" or "thesis".
const char* view_method_name(ViewMethod method);
// The inverse; nullopt for anything else.
std::optional<ViewMethod> parse_view_method(const std::string& name);

struct OrientationOptions {
  ViewMethod method = ViewMethod::kRobust;
  bool use_skeleton = true;   // false: depth only even when bodies exist (evaluation of the depth path)
  bool use_faces = true;      // face detector on the colour image (thesis: the face flag)
  std::string face_cascade;   // empty: default_face_cascade()
  double sides_weight = 1.0;  // evidence of the skeleton's own left/right (Kinect assumes people face it)
  double face_weight = 2.0;   // a frontal face found in the head region
  int face_every = 5;  // a track with saturated facing evidence runs the face detector every N-th frame only
  double no_face_weight = 0.3;  // a large, visible head region without a face (weak: detectors miss)
  double motion_weight = 0.8;   // walking direction, scaled by speed up to 1 m/s (below sides: people sidestep)
  double min_speed_mps = 0.25;  // slower bodies give no motion evidence
  double walk_axis_speed_mps = 0.5;  // depth only: at least this fast, the walking direction is the yaw
  double continuity_weight = 3.0;  // cap of the evidence a track accumulates for its facing direction
  double smoothing = 0.8;  // alpha of the alpha-beta yaw filter: weight of the new observation (1 = none)
  double turn_gain = 0.15;  // beta: how fast the filter's turning rate follows (0 = plain smoothing)
  double forget_s = 1.0;   // a track unseen this long starts afresh
  // Throws UsageError on weights < 0 or smoothing outside (0, 1].
  void check() const;
};

// One body to orient: its skeleton (or none) and its pixels (a body index or segmentation labels and the
// label value; empty labels when none). `key` identifies the track across frames (the Kinect tracking
// id, or a segment tracker's id).
struct BodyRef {
  uint64_t key = 0;
  const Body* body = nullptr;
  cv::Mat labels;  // CV_8U depth size, or empty
  int label = -1;
  static BodyRef of(const Body& b, const cv::Mat& body_index) { return {b.tracking_id, &b, body_index, b.index}; }
};

// Depth-only axis of a body: the principal direction of its horizontal torso points.
struct DepthAxis {
  double yaw_deg = 0;      // one of the two facing directions (the other is +180)
  double quality = 0;      // 0..1
  cv::Vec3d centroid{0, 0, 0};
  double height_m = 0;     // vertical extent of the body's points
  int points = 0;
};
// nullopt when the body has fewer than 200 pixels with depth. REQUIRES depth CV_16U and labels CV_8U of
// the depth intrinsics' size.
std::optional<DepthAxis> depth_axis(const cv::Mat& depth, double depth_unit_m, const Intrinsics& depth_k,
                                    const cv::Mat& labels, int label);

// Expected head box in colour pixels: from the Head joint (0.30 m tall box), or from the top of the
// body's pixels; empty when neither exists.
cv::Rect2d head_region(const RecordingMeta& meta, const RgbdFrame& frame, const BodyRef& ref);

class OrientationEstimator {
 public:
  // Throws UsageError on bad options, InputError when the face cascade cannot be loaded (only when
  // use_faces).
  explicit OrientationEstimator(const RecordingMeta& meta, OrientationOptions options = {});
  ~OrientationEstimator();

  // Orientation of one body in `frame`. Call once per body and frame, frames in time order (the track
  // state keyed by ref.key uses frame.time_s). Thesis method: thesis_view() with the face flag from the
  // face detector (unknown without colour); no state. `known_face` replaces the face detector (e.g. an
  // evaluation's oracle from the truth yaw, or a face found elsewhere).
  ViewEstimate estimate(const RgbdFrame& frame, const BodyRef& ref, std::optional<bool> known_face = std::nullopt);

  // The face detector's last answer for the body just estimated (for the partial scan and printing).
  const FaceResult& last_face() const { return last_face_; }
  const OrientationOptions& options() const { return options_; }

 private:
  struct Track;
  std::optional<bool> face_flag(const RgbdFrame& frame, const BodyRef& ref);
  RecordingMeta meta_;
  OrientationOptions options_;
  std::unique_ptr<FaceDetector> faces_;
  std::map<uint64_t, Track> tracks_;
  FaceResult last_face_;
};

}  // namespace bodyrec
