// `bodyrec detect`: people detection on a video, images or a camera.
#include <iostream>

#include "bodyrec/io/frame_source.h"
#include "command.h"
#include "common_options.h"
#include "detection_job.h"
#include "stop_signal.h"

namespace bodyrec::cli {
namespace {

struct DetectCommand {
  SourceOptions source;
  OutputOptions outputs;
  DetectorOptions detector;

  void run() const {
    StopOnSignal stop;  // SIGINT/SIGTERM end a live run after its frame, outputs whole, exit 0
    auto frames = open_source(source);
    auto people = make_detector(detector, *frames);
    const auto stats = run_detection(*frames, *people, outputs, true, nullptr);
    if (stats.stopped) std::cerr << "bodyrec detect: stopped by a signal after " << stats.frames << " frames\n";
    if (!outputs.quiet && !outputs.jsonl.empty())
      std::cerr << "bodyrec detect: " << stats.frames << " frames, "
                << (stats.frames ? stats.detector_ms / stats.frames : 0.0) << " ms per frame (" << people->describe()
                << ")\n";
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<DetectCommand>();
  CLI::App* sub = app.add_subcommand("detect", "Detect people in a video, images or a camera stream");
  sub->footer(
      "Writes one JSON object per frame: {\"frame\":N,\"time\":S,\"detections\":[{\"box\":[x,y,w,h],\"score\":s}]}\n"
      "Example: bodyrec detect /usr/share/doc/opencv-doc/examples/data/vtest.avi --jsonl out/detect.jsonl "
      "--annotate out/detect.avi\n"
      "Photos (people of any size, no motion): bodyrec detect photos/ --preset photo --annotate out/photos/");
  add_source_options(*sub, command->source);
  add_output_options(*sub, command->outputs);
  add_detector_options(*sub, command->detector, DetectorUse::kDetect);
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 10, add});

}  // namespace
}  // namespace bodyrec::cli
