#include "segment_options.h"

#include "bodyrec/core/error.h"
#include "option_checks.h"

namespace bodyrec::cli {

void add_segment_options(CLI::App& sub, SegmentCliOptions& options) {
  sub.add_option("--background", options.background,
                 "Background depth model: auto (learn it when the recording has >= 10 frames), on, off")
      ->check(one_of({"auto", "on", "off"}))
      ->capture_default_str();
  sub.add_option("--background-samples", options.background_samples, "Frames (spread over the recording) to learn it from")
      ->check(in_range(1, 100000))
      ->capture_default_str();
  sub.add_option("--min-height", options.segment.min_height_m, "Lowest person top above the ground, metres")
      ->check(in_range(0.3, 3.0))
      ->capture_default_str();
  sub.add_option("--max-height", options.segment.max_height_m, "Highest person top above the ground, metres")
      ->check(in_range(0.5, 3.5))
      ->capture_default_str();
}

DepthSegmenter make_segmenter(const RecordingReader& reader, const SegmentCliOptions& options) {
  if (options.segment.min_height_m >= options.segment.max_height_m)
    throw UsageError("--min-height must be below --max-height");
  DepthSegmenter segmenter(reader.meta().depth, reader.meta().depth_unit_m, options.segment);
  if (options.background == "on") {
    if (reader.frame_count() < 2)
      throw UsageError("--background on needs a recording of at least 2 frames (it has " +
                       std::to_string(reader.frame_count()) + ")");
    learn_recording_background(reader, segmenter, options.background_samples, 2);
  } else if (options.background == "auto") {
    learn_recording_background(reader, segmenter, options.background_samples, 10);
  }
  return segmenter;
}

DepthSegmenter make_segmenter(const RecordingMeta& meta, const SegmentCliOptions& options) {
  if (options.segment.min_height_m >= options.segment.max_height_m)
    throw UsageError("--min-height must be below --max-height");
  if (options.background == "on")
    throw UsageError("--background on learns from a recording's frames; a live sensor has none beforehand");
  return DepthSegmenter(meta.depth, meta.depth_unit_m, options.segment);
}

}  // namespace bodyrec::cli
