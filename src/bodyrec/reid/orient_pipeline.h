// Bodies and their views, frame by frame (thesis Ch6): RgbdBodyFinder finds the bodies of an RGB-D frame,
// OrientationEstimator gives each its view (F, FR, ... BL) and face. What `bodyrec orient` and
// `eval orient` run, and the first stage of ReidPipeline.
//
//   OrientPipeline orient(meta, options, segmenter);
//   for (each frame of a recording or sensor) { const OrientResult r = orient.process(frame); ... }
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bodyrec/reid/orientation_estimator.h"
#include "bodyrec/reid/rgbd_bodies.h"

namespace bodyrec {

struct OrientPipelineOptions {
  RgbdBodiesOptions bodies;
  OrientationOptions orientation;  // orientation.use_skeleton is set from !bodies.depth_only
  // Evaluation only: the face flag from the truth yaw (|yaw| < 90 degrees) instead of the face detector.
  bool face_oracle = false;
  void check() const;  // UsageError naming the field
};

struct OrientedBody {
  uint64_t key = 0;      // stays with the body while it is in view (rgbd_bodies.h)
  int slot = -1;         // label in the frame's labels (body index or segmentation), -1 none
  const Body* body = nullptr;  // the skeleton, when the body has one (points into the frame)
  ViewEstimate view;
  FaceResult face;
  int truth = -1;        // index into frame.truth->people, -1 when unknown
};

struct OrientResult {
  cv::Mat labels;        // the label image the slots refer to (may be empty)
  std::vector<OrientedBody> bodies;
  std::vector<BodyRef> refs;  // same order as bodies
  double ms = 0;         // orientation time (all bodies)
};

class OrientPipeline {
 public:
  // Errors as RgbdBodyFinder and OrientationEstimator say; `name` names the source in them.
  OrientPipeline(const RecordingMeta& meta, const OrientPipelineOptions& options,
                 std::optional<DepthSegmenter> segmenter, const std::string& name = "recording");
  // One frame (frames in time order). The result points into `frame` (skeletons): keep the frame alive.
  OrientResult process(const RgbdFrame& frame);
  const RecordingMeta& meta() const { return meta_; }

 private:
  RecordingMeta meta_;
  OrientPipelineOptions options_;
  RgbdBodyFinder finder_;
  OrientationEstimator estimator_;
};

}  // namespace bodyrec
