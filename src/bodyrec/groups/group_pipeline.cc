#include "bodyrec/groups/group_pipeline.h"

#include <chrono>

#include "bodyrec/core/error.h"

namespace bodyrec {

void GroupPipelineOptions::check() const {
  if (!(fps >= 0)) throw UsageError("GroupPipelineOptions.fps must be >= 0");
  tracking.check();
  stages.check();
}

GroupPipeline::GroupPipeline(PeopleDetector& detector, const GroupPipelineOptions& options,
                             std::shared_ptr<const GroundPlane> ground)
    : options_((options.check(), options)), tracking_(detector, options.tracking), stages_(options.stages, std::move(ground)) {}

GroupPipelineResult GroupPipeline::process(const Frame& frame) {
  GroupPipelineResult out;
  const auto t0 = std::chrono::steady_clock::now();
  out.tracks = tracking_.step(frame.index, frame.image);
  out.detected = tracking_.last_was_full();
  // Same precision as every sink writes, so results re-read from a file score the same.
  for (auto& t : out.tracks) t.box = round_box_for_output(t.box);
  out.tracking_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  out.time_s = options_.fps > 0 ? frame.index / options_.fps : frame.time_s;
  out.groups = stages_.process(frame.image, out.time_s, out.tracks);
  return out;
}

}  // namespace bodyrec
