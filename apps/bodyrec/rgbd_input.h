// An RGB-D source for the commands that read one (reid, orient, segment, greenscreen, contour): a
// recording folder, or a live OpenNI2 sensor (`--sensor [URI]`, the device code `record` uses). A sensor,
// or a recording played with --realtime, goes through the live frame loop (frame_loop.h).
#pragma once

#include <climits>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "bodyrec/rgbd/openni_source.h"
#include "bodyrec/rgbd/recording.h"
#include "frame_loop.h"

namespace bodyrec::cli {

struct LiveCliOptions {
  bool sensor = false;   // --sensor given
  std::string uri;       // its URI; "" = the first device
  bool realtime = false; // --realtime
  int queue = 1;         // --queue
  int test_delay_ms = 0; // hidden --test-delay-ms: a slow stage per frame, for tests of dropping
  bool live() const { return sensor || realtime; }
};

// --sensor [URI]; with `realtime`, --realtime and --queue too (`video`: the help names videos); the hidden
// --test-delay-ms. The command's positional input then becomes optional (check_input_given).
void add_live_options(CLI::App& sub, LiveCliOptions& options, bool realtime = true, bool video = false);

// UsageError unless exactly one of an input path, --sensor and (for a command with --camera, `camera`
// given) --camera N is given, and --realtime only with a file.
void check_input_given(const std::string& path, const LiveCliOptions& live, std::optional<int> camera = std::nullopt);

class RgbdInput {
 public:
  // The sensor when live.sensor (InputError with one line when there is no device or no OpenNI2 in this
  // build), else the recording at `path` (InputError as RecordingReader says).
  RgbdInput(const std::string& path, const LiveCliOptions& live);
  const RecordingMeta& meta() const { return sensor_ ? sensor_->meta() : reader_->meta(); }
  const std::string& name() const { return name_; }
  int frame_count() const { return sensor_ ? INT_MAX : reader_->frame_count(); }
  // The recording (none for a sensor): what learns a depth background before the run.
  const RecordingReader* recording() const { return reader_ ? &*reader_ : nullptr; }
  bool read(RgbdFrame& frame);

 private:
  std::string name_;
  std::unique_ptr<OpenNiSource> sensor_;
  std::optional<RecordingReader> reader_;
};

// The loop options for this input: live for a sensor or --realtime, paced for --realtime.
FrameLoopOptions loop_options(const LiveCliOptions& live, int max_frames);

// Runs the frames of `input` through `sink` as loop_options() says, sleeping test_delay_ms per frame.
FrameLoopStats run_rgbd_loop(RgbdInput& input, const LiveCliOptions& live, int max_frames,
                             const std::function<void(RgbdFrame&, const FrameArrival&)>& sink);

}  // namespace bodyrec::cli
