// `bodyrec eval track`: tracking scores (CLEAR MOT and IDF1) against PETS/CVML XML or MOT ground truth.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/eval/tracking_metrics.h"
#include "bodyrec/io/ground_truth.h"
#include "bodyrec/io/json_numbers.h"
#include "command.h"
#include "common_options.h"
#include "tracking_job.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

struct EvalTrackCommand {
  SourceOptions source;
  OutputOptions outputs;
  DetectorOptions detector;
  TrackingJobOptions tracking;
  std::string gt;
  double iou = 0.5;
  bool json = false;

  void run() const {
    if (source.path.empty()) throw UsageError("eval track needs --source VIDEO");
    tracking.tracker.check();
    const GroundTruth truth = read_ground_truth(gt);
    const auto truth_by_frame = truth.by_frame();
    auto frames = open_source(source);
    auto people = make_detector(detector, *frames);
    TrackingEvaluator evaluator(iou);
    const std::vector<LabelledBox> none;
    const auto stats = run_tracking(
        *frames, *people, tracking, outputs, !outputs.jsonl.empty(),
        [&](const Frame& frame, const std::vector<TrackedPerson>& tracks) {
          if (frame.index >= truth.frame_count) return;  // beyond the ground truth
          std::vector<LabelledBox> hypotheses;
          for (const auto& t : tracks) {
            LabelledBox b;
            b.frame = frame.index;
            b.id = t.id;
            b.box = t.box;
            hypotheses.push_back(b);
          }
          const auto it = truth_by_frame.find(frame.index);
          evaluator.add_frame(hypotheses, it == truth_by_frame.end() ? none : it->second);
        });
    const TrackingScores s = evaluator.scores();
    // No truth in the frames processed: MOTA would be a meaningless 0.
    if (s.ground_truth == 0)
      throw InputError(gt + ": no ground-truth box in the " + std::to_string(stats.frames) +
                       " frames processed (is it this source's ground truth, and its frames?)");
    const double ms = stats.frames ? stats.processing_ms / stats.frames : 0.0;
    std::printf("detector      %s (every %d frames; %s in between)\n", people->describe().c_str(),
                tracking.detect_every, tracking.between == BetweenDetections::kLocal ? "searched near tracks" : "predicted");
    std::printf("frames        %d scored (of %d processed)\n", s.frames, stats.frames);
    std::printf("ground truth  %d boxes; tracks %d boxes\n", s.ground_truth, s.hypotheses);
    std::printf("MOTA          %.4f\n", s.mota);
    std::printf("MOTP          %.4f (mean IoU of matches at IoU >= %.2f)\n", s.motp, iou);
    std::printf("IDF1          %.4f (IDP %.4f, IDR %.4f)\n", s.idf1, s.idp, s.idr);
    std::printf("FP            %d\n", s.fp);
    std::printf("FN            %d\n", s.fn);
    std::printf("ID switches   %d\n", s.id_switches);
    std::printf("ms per frame  %.2f (detector + tracker)\n", ms);
    if (json) {
      const nlohmann::json j = {{"mota", s.mota},          {"motp", s.motp},   {"idf1", s.idf1},
                                {"id_switches", s.id_switches}, {"fp", s.fp}, {"fn", s.fn},
                                {"frames", s.frames},      {"ms_per_frame", ms}};
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& eval) {
  auto command = std::make_shared<EvalTrackCommand>();
  CLI::App* sub = eval.add_subcommand("track", "Score people tracking against ground truth (MOTA, MOTP, IDF1)");
  sub->footer("Example: bodyrec eval track --source /usr/share/doc/opencv-doc/examples/data/vtest.avi "
              "--gt ../shared/datasets/pets09_s2l1/PETS2009-S2L1.xml --json");
  add_source_options(*sub, command->source, true);
  sub->add_option("--gt", command->gt, "Ground truth with ids: PETS/CVML XML (.xml) or MOTChallenge gt.txt")
      ->required();
  sub->add_option("--iou", command->iou, "IoU a track box needs to match a ground-truth box")
      ->check(in_range(0.05, 1.0));
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (mota, motp, idf1, id_switches, fp, fn, frames, ms_per_frame)");
  add_output_options(*sub, command->outputs);
  add_detector_options(*sub, command->detector, DetectorUse::kTrack);
  add_tracker_options(*sub, command->tracking);
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"eval", 20, add});

}  // namespace
}  // namespace bodyrec::cli
