// The tracking loop shared by `track` and `eval track`: frames -> detector (every Nth frame) -> tracker
// -> sinks. Kept apart from detection_job so that the detection loop stays as it is.
#pragma once

#include <functional>
#include <vector>

#include "bodyrec/detection/people_detector.h"
#include "bodyrec/io/frame_source.h"
#include "bodyrec/tracking/detect_and_track.h"
#include "common_options.h"

namespace bodyrec::cli {

using TrackingJobOptions = DetectAndTrackOptions;

// --detect-every and every TrackerOptions field (--min-hits, --max-age, --coast, --iou-gate, ...).
// Returns the options it added (for a command where they apply only with a flag: `needs`).
std::vector<CLI::Option*> add_tracker_options(CLI::App& sub, TrackingJobOptions& options);

struct TrackingRunStats {
  int frames = 0;
  int detected_frames = 0;
  double processing_ms = 0;  // detector + tracker time (not decoding or writing)
  bool stopped = false;      // SIGINT/SIGTERM ended the run early (a StopOnSignal was alive)
};

// Runs detection and tracking on every frame of `source`, writes JSONL (when `write_jsonl`:
// {"frame","time","tracks":[{"id","box":[x,y,w,h],"state"}]}), MOT rows with track ids and annotated
// frames with ids as `outputs` asks, and calls `on_frame` with each frame's reported tracks. Outputs are
// flushed per frame.
TrackingRunStats run_tracking(FrameSource& source, PeopleDetector& detector, const TrackingJobOptions& options,
                              const OutputOptions& outputs, bool write_jsonl,
                              const std::function<void(const Frame&, const std::vector<TrackedPerson>&)>& on_frame);

}  // namespace bodyrec::cli
