// Options of the depth-only segmentation shared by `segment`, `eval segment` and `contour`.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "bodyrec/rgbd/recording.h"
#include "bodyrec/rgbd/segment.h"

namespace bodyrec::cli {

struct SegmentCliOptions {
  std::string background = "auto";  // auto: learn when the recording has >= 10 frames; on; off
  int background_samples = 60;
  SegmentOptions segment;
};

// --background, --background-samples, --min-height, --max-height.
void add_segment_options(CLI::App& sub, SegmentCliOptions& options);

// A segmenter for the recording, with its background learnt as --background says (UsageError for
// "on" with fewer than 2 frames).
DepthSegmenter make_segmenter(const RecordingReader& reader, const SegmentCliOptions& options);
// A segmenter for a live sensor: no background learnt beforehand (ground plane only; UsageError for
// --background on).
DepthSegmenter make_segmenter(const RecordingMeta& meta, const SegmentCliOptions& options);

}  // namespace bodyrec::cli
