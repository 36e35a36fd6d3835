// The detection loop shared by `detect` and `eval detect`: frames -> detector -> sinks.
#pragma once

#include <functional>
#include <vector>

#include "bodyrec/detection/people_detector.h"
#include "bodyrec/io/frame_source.h"
#include "common_options.h"

namespace bodyrec::cli {

struct DetectionRunStats {
  int frames = 0;
  double detector_ms = 0;  // time spent in the detector only (not decoding or writing)
  bool stopped = false;    // SIGINT/SIGTERM ended the run early (a StopOnSignal was alive)
};

// Runs `detector` on every frame of `source`, writes JSONL (when `write_jsonl`), MOT and annotated
// output as `outputs` asks, and calls `on_frame` with each frame's detections. Outputs are flushed per
// frame; an exception leaves what was written so far valid.
DetectionRunStats run_detection(FrameSource& source, PeopleDetector& detector, const OutputOptions& outputs,
                                bool write_jsonl,
                                const std::function<void(const Frame&, const std::vector<Detection>&)>& on_frame);

}  // namespace bodyrec::cli
