// Online re-identification of an RGB-D stream, frame by frame (thesis Ch6, 3D Partial Scans Models, several
// people at once): bodies and views (OrientPipeline), the floor (a RANSAC plane refitted every 10 frames),
// partial scans of the bodies the decisions want and their statures, then OnlineReid's decisions on a
// ReidStore. What `bodyrec reid` and `eval reid-stream` run; a program of its own uses it the same way:
//
//   Gallery gallery("gallery.db", {.create = true});
//   auto matcher = make_matcher("stripes");
//   GalleryReidStore store(gallery, *matcher, {"sensor 1"});
//   ReidPipeline reid(meta, store, *matcher, options, segmenter);
//   for (each frame) { const ReidResult r = reid.process(frame); ... r.step.identities, r.step.events ... }
//   const std::vector<ReidEvent> last = reid.finish();  // `left` for everyone still in view
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bodyrec/reid/online_reid.h"
#include "bodyrec/reid/orient_pipeline.h"
#include "bodyrec/reid/partial_scan.h"
#include "bodyrec/rgbd/ground_plane.h"

namespace bodyrec {

struct ReidPipelineOptions {
  OrientPipelineOptions orient;
  OnlineReidOptions reid;
  // Frames a body without a measured stature waits before it is recognised as a user of known stature
  // (OnlineReidOptions::stature_wait_frames). None: reid's value with the sensor's bodies, 0 with bodyrec's
  // own depth segmentation, whose statures are often refused (people side by side).
  std::optional<int> stature_wait_frames;
};

struct ReidResult {
  std::vector<OrientedBody> bodies;  // same order as step.identities
  ReidStep step;
  double ms_orient = 0, ms_scan = 0, ms_reid = 0;
};

class ReidPipeline {
 public:
  // `store` and `matcher` must outlive the pipeline. Errors as OrientPipeline, PartialScanExtractor and
  // OnlineReid say.
  ReidPipeline(const RecordingMeta& meta, ReidStore& store, const AppearanceMatcher& matcher,
               const ReidPipelineOptions& options, std::optional<DepthSegmenter> segmenter,
               const std::string& name = "recording");
  // One frame (frames in time order; the result points into `frame`: keep it alive while reading it).
  ReidResult process(const RgbdFrame& frame);
  // Decides what can be decided and ends every track (`left`): at the end of a recording or a live run.
  std::vector<ReidEvent> finish() { return reid_.finish(); }
  const OnlineReid& decisions() const { return reid_; }

 private:
  static OnlineReidOptions resolved(const RecordingMeta& meta, const ReidPipelineOptions& options);

  RecordingMeta meta_;
  OrientPipeline orient_;
  PartialScanExtractor scans_;
  GroundPlaneTracker floor_;
  OnlineReid reid_;
  std::map<uint64_t, cv::Rect> last_box_;  // per track: the colour box of its last scan
};

}  // namespace bodyrec
