#include "bodyrec/reid/reid_pipeline.h"

#include <chrono>

#include "bodyrec/reid/body_measures.h"

namespace bodyrec {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

OnlineReidOptions ReidPipeline::resolved(const RecordingMeta& meta, const ReidPipelineOptions& options) {
  OnlineReidOptions o = options.reid;
  if (options.stature_wait_frames) o.stature_wait_frames = *options.stature_wait_frames;
  else if (uses_own_segmentation(meta, options.orient.bodies)) o.stature_wait_frames = 0;
  return o;
}

ReidPipeline::ReidPipeline(const RecordingMeta& meta, ReidStore& store, const AppearanceMatcher& matcher,
                           const ReidPipelineOptions& options, std::optional<DepthSegmenter> segmenter,
                           const std::string& name)
    : meta_(meta),
      orient_(meta, options.orient, std::move(segmenter), name),
      scans_(meta),
      floor_(meta.depth, meta.depth_unit_m),
      reid_(store, matcher, resolved(meta, options)) {}

ReidResult ReidPipeline::process(const RgbdFrame& frame) {
  OrientResult oriented = orient_.process(frame);
  ReidResult out;
  out.ms_orient = oriented.ms;
  auto t0 = std::chrono::steady_clock::now();
  // The floor: heights for the scans' bands and the statures.
  const std::optional<GroundPlane>& ground = floor_.update(frame.index, frame.depth);
  std::vector<ReidBody> bodies;
  for (size_t i = 0; i < oriented.bodies.size(); ++i) {
    const OrientedBody& b = oriented.bodies[i];
    ReidBody rb;
    rb.track = b.key;
    rb.view = b.view;
    if (reid_.wants_scan(b.key, b.view)) {
      rb.scan = scans_.extract(frame, oriented.refs[i], b.view, nullptr, ground ? &*ground : nullptr);
      if (rb.scan) last_box_[b.key] = rb.scan->box;
      if (ground && rb.scan)
        rb.stature_m = measure_stature(frame.depth, meta_.depth_unit_m, meta_.depth, oriented.labels, b.slot, *ground);
    }
    const auto box = last_box_.find(b.key);
    if (box != last_box_.end()) rb.box = box->second;
    bodies.push_back(std::move(rb));
  }
  out.ms_scan = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  out.step = reid_.step(frame.time_s, bodies);
  out.ms_reid = ms_since(t0);
  for (const ReidEvent& e : out.step.events)
    if (e.kind == ReidEventKind::kLeft) last_box_.erase(e.track);
  out.bodies = std::move(oriented.bodies);
  return out;
}

}  // namespace bodyrec
