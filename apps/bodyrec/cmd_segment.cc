// `bodyrec segment REC`: depth-only people segmentation (no body index) of a recording: per-frame people
// with boxes as JSON lines, optional label masks as PNG (thesis Ch5 without the Kinect SDK).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/frame_folder.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/io/sinks.h"
#include "bodyrec/rgbd/recording.h"
#include "bodyrec/rgbd/segment.h"
#include "command.h"
#include "rgbd_input.h"
#include "run_sinks.h"
#include "segment_options.h"

namespace bodyrec::cli {
namespace {

struct SegmentCommand {
  std::string recording, jsonl, masks;
  SegmentCliOptions seg;
  LiveCliOptions live;
  int max_frames = -1;
  bool json = false, quiet = false;

  void run() const {
    check_input_given(recording, live);
    StopOnSignal stop;  // SIGINT/SIGTERM end a live run with its outputs whole
    RgbdInput input(recording, live);
    if (!input.meta().streams.depth) throw InputError(input.name() + ": segment needs a depth stream");
    std::optional<FrameFolder> mask_files;
    if (!masks.empty()) mask_files.emplace(masks);
    DepthSegmenter segmenter =
        input.recording() ? make_segmenter(*input.recording(), seg) : make_segmenter(input.meta(), seg);
    std::unique_ptr<JsonlWriter> out;
    if (!quiet || !jsonl.empty()) out = std::make_unique<JsonlWriter>(jsonl);
    int last_people = 0;
    double ms = 0;
    const FrameLoopStats stats = run_rgbd_loop(input, live, max_frames, [&](RgbdFrame& f, const FrameArrival& arrival) {
      const auto t0 = std::chrono::steady_clock::now();
      const Segmentation s = segmenter.segment(f.depth);
      ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      last_people = static_cast<int>(s.people.size());
      if (out) {
        nlohmann::json line = segmentation_to_json(f.index, s);
        if (live.live()) line["dropped"] = arrival.dropped;
        out->write(line);
      }
      if (mask_files) {
        const std::string file = mask_files->file(f.index);
        if (!cv::imwrite(file, s.labels)) throw ProcessingError(file + ": cannot write image");
      }
    });
    if (mask_files) note_stale_frames(mask_files->stale_note());
    const int frames = stats.frames;
    const double per_frame = frames ? ms / frames : 0.0;
    if (!quiet || json)
      std::fprintf(stderr, "segmented %d frames, %d people in the last; %.2f ms per frame (%s)\n", frames, last_people,
                   per_frame, segmenter.has_background() ? "background model + ground plane" : "ground plane only");
    if (json) {
      const nlohmann::json j = {{"frames", frames},
                                {"people", last_people},
                                {"background", segmenter.has_background()},
                                {"ms_per_frame", per_frame},
                                {"dropped", stats.dropped}};
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<SegmentCommand>();
  CLI::App* sub = app.add_subcommand("segment", "Find people in depth alone (background, ground plane, clusters)");
  sub->add_option("REC", command->recording, "Recording directory with a depth stream (or --sensor)");
  add_live_options(*sub, command->live);
  sub->add_option("--jsonl", command->jsonl, "Per-frame people and boxes as JSON lines; default stdout");
  sub->add_option("--masks", command->masks, "Folder for NNNNNN.png label masks (0..5 person, 255 none)");
  add_segment_options(*sub, command->seg);
  sub->add_option("--max-frames", command->max_frames, "Stop after this many frames; -1 = all");
  sub->add_flag("-q,--quiet", command->quiet, "No JSON lines on stdout (unless --jsonl FILE)");
  sub->add_flag("--json", command->json, "End stdout with one JSON object (frames, people in the last frame, ms_per_frame, dropped)");
  sub->footer(
      "Example: bodyrec import pcd five_people.pcd --out rec && bodyrec segment rec --json\n"
      "         bodyrec segment rec_synth --masks masks --jsonl people.jsonl --json\n"
      "         bodyrec segment --sensor --jsonl live.jsonl   (a live OpenNI2 sensor, until Ctrl-C)");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 53, add});

}  // namespace
}  // namespace bodyrec::cli
