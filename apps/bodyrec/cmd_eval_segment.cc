// `bodyrec eval segment REC`: scores the depth-only segmentation against the recording's body index
// (per-person mask IoU with an optimal one-to-one matching per frame).
#include <chrono>
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/io/sinks.h"
#include "bodyrec/rgbd/recording.h"
#include "bodyrec/rgbd/segment.h"
#include "command.h"
#include "segment_options.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

struct EvalSegmentCommand {
  std::string recording, jsonl;
  SegmentCliOptions seg;
  int max_frames = -1, min_pixels = 500;
  bool json = false;

  void run() const {
    RecordingReader reader(recording);
    if (!reader.meta().streams.depth || !reader.meta().streams.body_index)
      throw InputError(recording + ": eval segment needs depth and body index streams");
    DepthSegmenter segmenter = make_segmenter(reader, seg);
    std::unique_ptr<JsonlWriter> per_frame_out;
    if (!jsonl.empty()) per_frame_out = std::make_unique<JsonlWriter>(jsonl);
    int frames = 0, persons = 0, found = 0, extra = 0;
    double ms = 0, iou_sum = 0;
    for (RgbdFrame f; (max_frames < 0 || frames < max_frames) && reader.read(f); ++frames) {
      const auto t0 = std::chrono::steady_clock::now();
      const Segmentation s = segmenter.segment(f.depth);
      ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      // Depth-only segmentation cannot label pixels without depth (dropouts, far range): score on the
      // body-index pixels that have depth.
      cv::Mat truth = f.body_index.clone();
      truth.setTo(cv::Scalar(kNoBody), f.depth == 0);
      const MaskMatch m = match_masks(truth, s.labels, min_pixels);
      for (double v : m.iou) {
        iou_sum += v;
        found += v > 0;
      }
      persons += static_cast<int>(m.iou.size());
      extra += m.unmatched_predicted;
      if (per_frame_out)
        per_frame_out->write({{"frame", f.index}, {"iou", m.iou}, {"extra", m.unmatched_predicted},
                              {"people", s.people.size()}});
    }
    const double mean_iou = persons ? iou_sum / persons : 0.0;
    const double per_frame = frames ? ms / frames : 0.0;
    std::printf("frames        %d (background model: %s)\n", frames, segmenter.has_background() ? "yes" : "no");
    std::printf("persons       %d person-frames with >= %d body-index pixels with depth; %d matched\n", persons, min_pixels, found);
    std::printf("mean IoU      %.4f (unmatched true persons count 0)\n", mean_iou);
    std::printf("extra people  %d segmented people without a true person\n", extra);
    std::printf("ms per frame  %.2f (segmentation only)\n", per_frame);
    if (json) {
      const nlohmann::json j = {{"mean_iou", mean_iou}, {"persons", persons}, {"matched", found},
                                {"extra", extra},       {"frames", frames},   {"ms_per_frame", per_frame}};
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<EvalSegmentCommand>();
  CLI::App* sub = app.add_subcommand("segment", "Score depth-only segmentation against the body index (mask IoU)");
  sub->add_option("REC", command->recording, "Recording with depth and body index (e.g. from bodyrec synth)")->required();
  add_segment_options(*sub, command->seg);
  sub->add_option("--jsonl", command->jsonl, "Per-frame IoUs (true persons by label) and extra people as JSON lines");
  sub->add_option("--min-pixels", command->min_pixels, "True persons with fewer body-index pixels with depth are not scored")
      ->check(in_range(0, 1000000))
      ->capture_default_str();
  sub->add_option("--max-frames", command->max_frames, "Stop after this many frames; -1 = all");
  sub->add_flag("--json", command->json, "End stdout with one JSON object (mean_iou, persons, frames, ms_per_frame)");
  sub->footer("Example: bodyrec synth --people 3 --seed 10 --frames 90 --out rec -q && bodyrec eval segment rec --json");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"eval", 53, add});

}  // namespace
}  // namespace bodyrec::cli
