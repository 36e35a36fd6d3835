// Shared by `groups` and `eval roles`: the options of the group-leader pipeline (groups/group_pipeline.h)
// and the loop source -> GroupPipeline -> sinks (JSONL, MOT rows of the tracks, annotated video).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "bodyrec/groups/group_pipeline.h"
#include "common_options.h"
#include "group_options.h"
#include "tracking_job.h"

namespace bodyrec::cli {

struct GroupsJobOptions {
  TrackingJobOptions tracking;
  GroupStagesOptions pipeline;
  GroupCliOptions membership;      // --window, --linkage, ... (shared with eval groups)
  std::string homography, calibration;
  double fps = 0;                  // time base override (0 = the source's)

  // The pipeline options with the membership options resolved; throws UsageError for bad values.
  GroupPipelineOptions resolved() const;
  // The ground plane from --homography or --calibration (null when neither); throws InputError.
  std::shared_ptr<const GroundPlane> ground_plane() const;
};

// Every option of the pipeline after tracking (and the tracker's own).
void add_groups_options(CLI::App& sub, GroupsJobOptions& options);

struct GroupsRunStats {
  int frames = 0;
  double tracking_ms = 0;  // detection + tracking
  StageTimes stages;       // summed over frames
  bool stopped = false;    // SIGINT/SIGTERM ended the run early (a StopOnSignal was alive)
  double total_ms() const {
    return tracking_ms + stages.motion + stages.groups + stages.roles + stages.leader + stages.flow;
  }
};

// Runs the whole pipeline; writes JSONL (when `write_jsonl`), MOT rows of the tracks and annotated frames
// in the thesis's colours as `outputs` asks, and calls `on_frame` with each frame's result.
GroupsRunStats run_groups(FrameSource& source, PeopleDetector& detector, const GroupsJobOptions& options,
                          const OutputOptions& outputs, bool write_jsonl,
                          const std::function<void(const Frame&, const GroupFrame&)>& on_frame);

}  // namespace bodyrec::cli
