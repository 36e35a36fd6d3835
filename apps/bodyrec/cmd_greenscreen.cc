// `bodyrec greenscreen REC --out DIR`: per-body background removal of a recording or a live sensor
// (thesis Ch5). Bodies come from the body index when the source has one, else from the depth-only
// segmentation (`segment`), as OpenNI2 sensors give no body index.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/frame_folder.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/rgbd/green_screen.h"
#include "bodyrec/rgbd/segment.h"
#include "command.h"
#include "rgbd_input.h"
#include "run_sinks.h"
#include "segment_options.h"
#include "stop_signal.h"

namespace bodyrec::cli {
namespace {

struct GreenScreenCommand {
  std::string recording, out;
  LiveCliOptions live;
  SegmentCliOptions seg;
  int max_frames = -1;
  bool json = false;

  void run() const {
    check_input_given(recording, live);
    StopOnSignal stop;  // SIGINT/SIGTERM end a live run after its frame, cut-outs written so far kept
    RgbdInput input(recording, live);
    const RecordingStreams& s = input.meta().streams;
    if (!s.color || !s.depth)
      throw InputError(input.name() + ": greenscreen needs colour and depth streams (and a body index, or depth to "
                                      "segment)");
    std::optional<DepthSegmenter> segmenter;  // no body index: people from depth alone
    if (!s.body_index)
      segmenter = input.recording() ? make_segmenter(*input.recording(), seg) : make_segmenter(input.meta(), seg);
    FrameFolder folder(out);
    BackgroundRemoval removal(input.meta());
    std::array<cv::Mat, kMaxBodies> cutouts;
    int written = 0;
    double ms = 0;
    const FrameLoopStats stats = run_rgbd_loop(input, live, max_frames, [&](RgbdFrame& f, const FrameArrival&) {
      const auto t0 = std::chrono::steady_clock::now();
      const cv::Mat bodies = segmenter ? segmenter->segment(f.depth).labels : f.body_index;
      removal.apply(f.depth, bodies, f.color, cutouts);
      ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      for (int b = 0; b < kMaxBodies; ++b) {
        if (cutouts[static_cast<size_t>(b)].empty()) continue;
        const std::string file = folder.file(f.index, "_body" + std::to_string(b));
        if (!cv::imwrite(file, cutouts[static_cast<size_t>(b)])) throw ProcessingError(file + ": cannot write image");
        ++written;
      }
    });
    note_stale_frames(folder.stale_note());
    const int frames = stats.frames;
    const double per_frame = frames ? ms / frames : 0.0;
    const char* bodies_from = segmenter ? "bodies from depth segmentation" : "bodies from the body index";
    std::printf("wrote %d BGRA cut-outs of %d frames to %s (%s); %.3f ms per frame (%s)\n", written, frames,
                out.c_str(), bodies_from, per_frame,
                segmenter ? "segmentation and background removal" : "background removal only");
    if (json) {
      const nlohmann::json j = {{"frames", frames},
                                {"cutouts", written},
                                {"ms_per_frame", per_frame},
                                {"bodies_from", segmenter ? "segmentation" : "body_index"},
                                {"dropped", stats.dropped}};
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<GreenScreenCommand>();
  CLI::App* sub = app.add_subcommand("greenscreen", "Cut each body out of a recording's or a sensor's colour (background removal)");
  sub->add_option("REC", command->recording,
                  "Recording directory with colour and depth (or --sensor); bodies from its body index, else from "
                  "depth segmentation");
  add_live_options(*sub, command->live);
  sub->add_option("--out", command->out, "Folder for NNNNNN_bodyS.png (depth-sized BGRA, transparent background)")->required();
  add_segment_options(*sub, command->seg);
  sub->add_option("--max-frames", command->max_frames, "Stop after this many frames; -1 = all");
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (frames, cutouts, ms_per_frame, bodies_from, dropped)");
  sub->footer(
      "Example: bodyrec synth --people 2 --frames 60 --out rec && bodyrec greenscreen rec --out cutouts\n"
      "         bodyrec greenscreen --sensor --out cutouts   (a live OpenNI2 sensor, until Ctrl-C)");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 52, add});

}  // namespace
}  // namespace bodyrec::cli
