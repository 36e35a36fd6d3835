// `bodyrec record --out DIR`: saves a live OpenNI2 stream (colour + depth) in the recording format.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/io/progress.h"
#include "bodyrec/rgbd/openni_source.h"
#include "bodyrec/rgbd/recording.h"
#include "command.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

struct RecordCommand {
  std::string out, device;
  int frames = 300;
  bool json = false, quiet = false;

  void run() const {
    OpenNiSource source(device);  // InputError (exit 3) without a device or without OpenNI2 support
    RecordingWriter writer(out, source.meta());
    const bool progress = progress_on_terminal(quiet);
    for (int i = 0; i < frames; ++i) {
      RgbdFrame f;
      source.read(f);
      writer.write(f);  // meta.json is rewritten per frame: an interrupted recording stays readable
      if (progress && (i + 1) % 30 == 0) std::fprintf(stderr, "recorded %d frames\n", i + 1);
    }
    if (!quiet || json)
      std::fprintf(stderr, "recorded %d frames from %s to %s\n", writer.frame_count(), source.meta().sensor.c_str(),
                   out.c_str());
    if (json) {
      const nlohmann::json j = {{"frames", writer.frame_count()}, {"sensor", source.meta().sensor}, {"out", out}};
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<RecordCommand>();
  CLI::App* sub = app.add_subcommand("record", "Record a live OpenNI2 RGB-D sensor (colour + depth) to a recording");
  sub->add_option("--out", command->out, "New recording directory (must not exist or be empty)")->required();
  sub->add_option("--frames", command->frames, "Frames to record")->check(in_range(1, 10000000))->capture_default_str();
  sub->add_option("--device", command->device, "OpenNI2 device URI; default the first device");
  sub->add_flag("-q,--quiet", command->quiet, "No progress on stderr (drawn only when stderr is a terminal)");
  sub->add_flag("--json", command->json, "End stdout with one JSON object (frames, sensor, out)");
  sub->footer(
      "Exit code 3 with a one-line message when there is no device or the build has no OpenNI2.\n"
      "Example: bodyrec record --out rec_live --frames 90 && bodyrec segment rec_live --json");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 49, add});

}  // namespace
}  // namespace bodyrec::cli
