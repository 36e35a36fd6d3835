// `bodyrec track`: multi-person tracking (detector + Kalman/Hungarian tracker) on a video, images or a camera.
#include <iostream>

#include "bodyrec/io/frame_source.h"
#include "command.h"
#include "common_options.h"
#include "stop_signal.h"
#include "tracking_job.h"

namespace bodyrec::cli {
namespace {

struct TrackCommand {
  SourceOptions source;
  OutputOptions outputs;
  DetectorOptions detector;
  TrackingJobOptions tracking;

  void run() const {
    tracking.tracker.check();
    StopOnSignal stop;  // SIGINT/SIGTERM end a live run after its frame, outputs whole, exit 0
    auto frames = open_source(source);
    auto people = make_detector(detector, *frames);
    const auto stats = run_tracking(*frames, *people, tracking, outputs, true, nullptr);
    if (stats.stopped) std::cerr << "bodyrec track: stopped by a signal after " << stats.frames << " frames\n";
    if (!outputs.quiet && !outputs.jsonl.empty())
      std::cerr << "bodyrec track: " << stats.frames << " frames (" << stats.detected_frames << " detected), "
                << (stats.frames ? stats.processing_ms / stats.frames : 0.0) << " ms per frame ("
                << people->describe() << ")\n";
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<TrackCommand>();
  CLI::App* sub = app.add_subcommand("track", "Track people (ids stable over time) in a video, images or a camera");
  sub->footer(
      "Writes one JSON object per frame: {\"frame\":N,\"time\":S,\"tracks\":[{\"id\":K,\"box\":[x,y,w,h],"
      "\"state\":\"confirmed\"|\"lost\"}]}\n"
      "Example: bodyrec track /usr/share/doc/opencv-doc/examples/data/vtest.avi --jsonl out/track.jsonl "
      "--mot out/track.txt --annotate out/track.avi");
  add_source_options(*sub, command->source);
  add_output_options(*sub, command->outputs);
  add_detector_options(*sub, command->detector, DetectorUse::kTrack);
  add_tracker_options(*sub, command->tracking);
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 20, add});

}  // namespace
}  // namespace bodyrec::cli
