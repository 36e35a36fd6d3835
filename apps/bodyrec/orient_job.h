// Shared by `bodyrec orient` and `bodyrec eval orient`: opens a recording or an NTU .skeleton file,
// finds the bodies of every frame (skeletons; else body-index slots; else depth-only segmentation, its
// people followed on the floor by tracking/floor_tracker.h) and orients each with the OrientationEstimator.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bodyrec/reid/orientation_estimator.h"
#include "bodyrec/rgbd/recording.h"
#include "segment_options.h"

namespace bodyrec::cli {

struct OrientCliOptions {
  std::string views = "robust";
  bool no_faces = false;
  bool depth_only = false;  // ignore skeletons: orient from the body pixels' depth
  // Where bodies come from: auto (skeletons, else body index, else own depth segmentation), skeleton,
  // body-index (slots only, as a sensor without skeletons gives them) or depth (own segmentation).
  std::string bodies_from = "auto";
  bool face_oracle = false; // eval only: the face flag from the truth yaw (|yaw| < 90) instead of the detector
  int max_frames = -1;
  SegmentCliOptions seg;
};

// --views, --no-faces, --depth-only, --bodies-from, --max-frames and the segmentation options.
void add_orient_options(CLI::App& sub, OrientCliOptions& options);

struct OrientedBody {
  uint64_t key = 0;      // tracking id; 1000000 + 10 x appearance + body-index slot (a new appearance when
                         // the slot went to another body: orient_job.cc SlotKeys); or 2000000 + floor track id
  int slot = -1;         // label in the frame's labels (body index or segmentation), -1 none
  const Body* body = nullptr;
  ViewEstimate view;
  FaceResult face;
  int truth = -1;        // index into frame.truth->people, -1 when unknown
};

struct OrientFrame {
  const RgbdFrame& frame;
  const cv::Mat& labels;  // the labels the slots refer to (may be empty)
  std::vector<OrientedBody> bodies;
  double ms = 0;          // orientation time for this frame (all bodies; not reading)
};

// Runs over every frame (up to max_frames) and calls `sink` per frame. Returns the number of frames.
// InputError/UsageError as the readers and options say; `sink` exceptions propagate.
int run_orientation(const std::string& input, const OrientCliOptions& options,
                    const std::function<void(const OrientFrame&)>& sink);

// The meta of a recording, or the fitted cameras of an NTU file (bodies only).
bool is_skeleton_file(const std::string& input);

// Whether run_orientation finds the bodies of a recording with `meta` by its own depth segmentation
// (--bodies-from depth, or auto on a recording with depth but neither body index nor usable skeletons).
bool uses_own_segmentation(const RecordingMeta& meta, const OrientCliOptions& options);

}  // namespace bodyrec::cli
