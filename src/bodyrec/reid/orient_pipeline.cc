#include "bodyrec/reid/orient_pipeline.h"

#include <chrono>
#include <cmath>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

OrientationOptions estimator_options(const OrientPipelineOptions& options) {
  OrientationOptions o = options.orientation;
  o.use_skeleton = !options.bodies.depth_only;
  return o;
}

}  // namespace

void OrientPipelineOptions::check() const {
  if (bodies.depth_only && orientation.method == ViewMethod::kThesis)
    throw UsageError("orientation: bodies.depth_only needs the robust view method (the thesis rule reads joint "
                     "quaternions)");
}

OrientPipeline::OrientPipeline(const RecordingMeta& meta, const OrientPipelineOptions& options,
                               std::optional<DepthSegmenter> segmenter, const std::string& name)
    : meta_(meta),
      options_((options.check(), options)),
      finder_(meta, options.bodies, std::move(segmenter), name),
      estimator_(meta, estimator_options(options)) {}

OrientResult OrientPipeline::process(const RgbdFrame& f) {
  FoundBodies found = finder_.find(f);
  OrientResult out;
  out.labels = found.labels;
  const auto t0 = std::chrono::steady_clock::now();
  for (const FoundBody& b : found.bodies) {
    OrientedBody ob;
    ob.key = b.ref.key;
    ob.slot = b.ref.label;
    ob.body = b.ref.body;
    ob.truth = b.truth;
    std::optional<bool> oracle;
    if (options_.face_oracle && f.truth && b.truth >= 0)
      oracle = std::abs(f.truth->people[static_cast<size_t>(b.truth)].yaw_deg) < 90;
    ob.view = estimator_.estimate(f, b.ref, oracle);
    ob.face = estimator_.last_face();
    out.bodies.push_back(ob);
    out.refs.push_back(b.ref);
  }
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace bodyrec
