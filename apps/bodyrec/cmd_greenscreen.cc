// `bodyrec greenscreen REC --out DIR`: per-body background removal of a recording (thesis Ch5).
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/rgbd/green_screen.h"
#include "command.h"

namespace bodyrec::cli {
namespace {

struct GreenScreenCommand {
  std::string recording, out;
  int max_frames = -1;
  bool json = false;

  void run() const {
    RecordingReader reader(recording);
    const RecordingStreams& s = reader.meta().streams;
    if (!s.color || !s.depth || !s.body_index)
      throw InputError(recording + ": greenscreen needs colour, depth and body index streams");
    std::error_code ec;
    std::filesystem::create_directories(out, ec);
    if (ec) throw ProcessingError(out + ": cannot create (" + ec.message() + ")");
    BackgroundRemoval removal(reader.meta());
    std::array<cv::Mat, kMaxBodies> cutouts;
    int frames = 0, written = 0;
    double ms = 0;
    for (RgbdFrame f; (max_frames < 0 || frames < max_frames) && reader.read(f); ++frames) {
      const auto t0 = std::chrono::steady_clock::now();
      removal.apply(f.depth, f.body_index, f.color, cutouts);
      ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      for (int b = 0; b < kMaxBodies; ++b) {
        if (cutouts[static_cast<size_t>(b)].empty()) continue;
        const std::string file = out + "/" + frame_stem(f.index) + "_body" + std::to_string(b) + ".png";
        if (!cv::imwrite(file, cutouts[static_cast<size_t>(b)])) throw ProcessingError(file + ": cannot write image");
        ++written;
      }
    }
    const double per_frame = frames ? ms / frames : 0.0;
    std::printf("wrote %d BGRA cut-outs of %d frames to %s; %.3f ms per frame (background removal only)\n", written,
                frames, out.c_str(), per_frame);
    if (json) {
      const nlohmann::json j = {{"frames", frames}, {"cutouts", written}, {"ms_per_frame", per_frame}};
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<GreenScreenCommand>();
  CLI::App* sub = app.add_subcommand("greenscreen", "Cut each body out of a recording's colour (background removal)");
  sub->add_option("REC", command->recording, "Recording directory with colour, depth and body index")->required();
  sub->add_option("--out", command->out, "Folder for NNNNNN_bodyS.png (512x424 BGRA, transparent background)")->required();
  sub->add_option("--max-frames", command->max_frames, "Stop after this many frames; -1 = all");
  sub->add_flag("--json", command->json, "End stdout with one JSON object (frames, cutouts, ms_per_frame)");
  sub->footer("Example: bodyrec synth --people 2 --frames 60 --out rec && bodyrec greenscreen rec --out cutouts");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 52, add});

}  // namespace
}  // namespace bodyrec::cli
