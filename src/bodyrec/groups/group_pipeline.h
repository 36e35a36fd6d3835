// The whole group-leader pipeline of thesis Ch4, frame by frame: people detection and tracking
// (tracking/detect_and_track.h), then motion, groups, roles, leader tracking and direction (GroupStages).
// What `bodyrec groups` and `eval roles` run; a program of its own uses it the same way:
//
//   HogPeopleDetector detector(HogPeopleOptions::preset(HogPreset::kDefault));
//   GroupPipeline groups(detector, {}, read_tsai_calibration("View_001.xml"));  // or nullptr: pixels
//   for (Frame f; source.read(f);) {
//     const GroupPipelineResult r = groups.process(f);  // r.groups.people: id, box, role, group; r.groups.leaders
//   }
#pragma once

#include <memory>
#include <vector>

#include "bodyrec/detection/people_detector.h"
#include "bodyrec/groups/group_stages.h"
#include "bodyrec/io/frame_source.h"
#include "bodyrec/io/ground_plane.h"
#include "bodyrec/tracking/detect_and_track.h"

namespace bodyrec {

struct GroupPipelineOptions {
  DetectAndTrackOptions tracking;
  GroupStagesOptions stages;
  // Frames per second for times and speeds; 0 = the frames' own times (Frame::time_s). A video whose header
  // is wrong (vtest.avi says 10, was recorded at 7) needs it.
  double fps = 0;
  void check() const;  // UsageError naming the field
};

struct GroupPipelineResult {
  double time_s = 0;                  // the frame's time on the pipeline's time base
  std::vector<TrackedPerson> tracks;  // the tracker's report, boxes rounded as the outputs write them
  bool detected = false;              // the full detector ran on this frame (else a local search or prediction)
  GroupFrame groups;                  // motion, people with roles and groups, leaders, per-stage times
  double tracking_ms = 0;             // detection + tracking on this frame
};

class GroupPipeline {
 public:
  // `detector` must outlive the pipeline; `ground` may be null (distances in pixels scaled by the people's
  // box heights). Calls options.check().
  GroupPipeline(PeopleDetector& detector, const GroupPipelineOptions& options,
                std::shared_ptr<const GroundPlane> ground);
  // One frame (frames in order).
  GroupPipelineResult process(const Frame& frame);
  const GroupStages& stages() const { return stages_; }

 private:
  GroupPipelineOptions options_;
  DetectAndTrack tracking_;
  GroupStages stages_;
};

}  // namespace bodyrec
