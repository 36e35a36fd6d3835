// Shared by `bodyrec orient`, `eval orient`, `reid` and `eval reid-stream`: the options of the bodies and
// views stage (reid/orient_pipeline.h), and the loop that reads a recording or an NTU .skeleton file
// frame by frame through an OrientPipeline.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bodyrec/reid/orient_pipeline.h"
#include "bodyrec/rgbd/recording.h"
#include "segment_options.h"

namespace bodyrec::cli {

struct OrientCliOptions {
  OrientPipelineOptions pipeline;
  int max_frames = -1;
  SegmentCliOptions seg;
};

// --views, --no-faces, --depth-only, --bodies-from, --max-frames and the segmentation options.
void add_orient_options(CLI::App& sub, OrientCliOptions& options);

struct OrientFrame {
  const RgbdFrame& frame;
  const OrientResult& result;
};

// An opened source of RGB-D frames for the orientation stage: a recording, or an NTU skeleton file (bodies
// only, cameras fitted to its joints) held in memory.
class OrientSource {
 public:
  // InputError naming the file when it cannot be read.
  explicit OrientSource(const std::string& input);
  const RecordingMeta& meta() const { return meta_; }
  const std::string& name() const { return name_; }
  int frame_count() const { return frames_; }
  bool read(RgbdFrame& frame);
  // The depth segmenter the options ask for (none when the bodies come from the sensor).
  std::optional<DepthSegmenter> segmenter(const OrientCliOptions& options) const;

 private:
  std::string name_;
  std::optional<RecordingReader> reader_;
  std::vector<std::vector<Body>> ntu_;
  RecordingMeta meta_;
  int frames_ = 0, next_ = 0;
};

// UsageError naming the flags for a combination the pipeline refuses.
void check_orient_options(const OrientCliOptions& options);

// Runs over every frame (up to max_frames) and calls `sink` per frame. Returns the number of frames.
// InputError/UsageError as the readers and options say; `sink` exceptions propagate.
int run_orientation(const std::string& input, const OrientCliOptions& options,
                    const std::function<void(const OrientFrame&)>& sink);

// Whether the input is an NTU RGB+D .skeleton file (else a recording directory).
bool is_skeleton_file(const std::string& input);

}  // namespace bodyrec::cli
