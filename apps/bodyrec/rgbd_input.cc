#include "rgbd_input.h"

#include <thread>

#include "bodyrec/core/error.h"
#include "option_checks.h"

namespace bodyrec::cli {

void add_live_options(CLI::App& sub, LiveCliOptions& o, bool realtime, bool video) {
  sub.add_option_function<std::vector<std::string>>(
         "--sensor",
         [&o](const std::vector<std::string>& uri) {
           o.sensor = true;
           o.uri = uri.empty() ? "" : uri.front();
         },
         "Read a live OpenNI2 RGB-D sensor instead of a recording: the device URI, or nothing for the first "
         "device (exit 3 with one line when there is none). Frames come through a grabber that drops the "
         "oldest when processing falls behind; SIGINT/SIGTERM end the run cleanly")
      ->expected(0, 1)
      ->type_name("[URI]");
  if (realtime) {
    sub.add_flag("--realtime", o.realtime,
                 std::string("Play the recording") + (video ? " or video" : "") +
                     " at its own frame rate through the live path (frames dropped when processing falls "
                     "behind, counted as \"dropped\")");
    sub.add_option("--queue", o.queue, "Live sources: frames waiting for processing before the oldest is dropped")
        ->check(in_range(1, 8))
        ->capture_default_str();
  }
  sub.add_option("--test-delay-ms", o.test_delay_ms)->group("")->check(non_negative());
}

void check_input_given(const std::string& path, const LiveCliOptions& live, std::optional<int> camera) {
  const bool on_camera = camera && *camera >= 0;
  const int given = !path.empty() + live.sensor + on_camera;
  const std::string choices = camera ? "a path, --sensor or --camera N" : "a recording or --sensor";
  if (given == 0) throw UsageError("no input: give " + choices);
  if (given > 1) throw UsageError("more than one input: give one of " + choices);
  if (live.realtime && (live.sensor || on_camera)) throw UsageError("--realtime plays a file; a device is live already");
}

RgbdInput::RgbdInput(const std::string& path, const LiveCliOptions& live) {
  if (live.sensor) {
    sensor_ = std::make_unique<OpenNiSource>(live.uri);
    name_ = "sensor " + (live.uri.empty() ? std::string("(first device)") : live.uri);
  } else {
    reader_.emplace(path);
    name_ = path;
  }
}

bool RgbdInput::read(RgbdFrame& frame) {
  if (sensor_) {
    sensor_->read(frame);
    return true;
  }
  return reader_->read(frame);
}

FrameLoopOptions loop_options(const LiveCliOptions& live, int max_frames) {
  FrameLoopOptions o;
  o.live = live.live();
  o.pace = live.realtime;
  o.queue = static_cast<size_t>(std::max(1, live.queue));
  o.max_frames = max_frames;
  return o;
}

FrameLoopStats run_rgbd_loop(RgbdInput& input, const LiveCliOptions& live, int max_frames,
                             const std::function<void(RgbdFrame&, const FrameArrival&)>& sink) {
  return run_frame_loop<RgbdFrame>([&input](RgbdFrame& f) { return input.read(f); },
                                   [](const RgbdFrame& f) { return f.time_s; }, loop_options(live, max_frames),
                                   [&](RgbdFrame& f, const FrameArrival& a) {
                                     if (live.test_delay_ms > 0)
                                       std::this_thread::sleep_for(std::chrono::milliseconds(live.test_delay_ms));
                                     sink(f, a);
                                   });
}

}  // namespace bodyrec::cli
