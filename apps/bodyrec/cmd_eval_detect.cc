// `bodyrec eval detect`: detection precision, recall and AP50 against PETS/CVML XML or MOT ground truth.
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/eval/detection_metrics.h"
#include "bodyrec/io/ground_truth.h"
#include "bodyrec/io/json_numbers.h"
#include "command.h"
#include "common_options.h"
#include "detection_job.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

struct EvalDetectCommand {
  SourceOptions source;
  OutputOptions outputs;
  DetectorOptions detector;
  std::string gt;
  double iou = 0.5;
  bool json = false;

  void run() const {
    if (source.path.empty()) throw UsageError("eval detect needs --source VIDEO");
    const GroundTruth truth = read_ground_truth(gt);
    const auto truth_by_frame = truth.by_frame();
    auto frames = open_source(source);
    auto people = make_detector(detector, frames->fps().has_value());
    DetectionEvaluator evaluator(iou);
    const std::vector<LabelledBox> none;
    const auto stats = run_detection(*frames, *people, outputs, !outputs.jsonl.empty(),
                                     [&](const Frame& frame, const std::vector<Detection>& detections) {
                                       if (frame.index >= truth.frame_count) return;  // beyond the ground truth
                                       const auto it = truth_by_frame.find(frame.index);
                                       evaluator.add_frame(detections, it == truth_by_frame.end() ? none : it->second);
                                     });
    const DetectionScores s = evaluator.scores();
    const double ms = stats.frames ? stats.detector_ms / stats.frames : 0.0;
    std::printf("detector      %s\n", people->describe().c_str());
    std::printf("frames        %d scored (of %d processed)\n", s.frames, stats.frames);
    std::printf("ground truth  %d boxes\n", s.ground_truth);
    std::printf("detections    %d (%d true, %d false at IoU >= %.2f)\n", s.detections, s.true_positives,
                s.false_positives, iou);
    std::printf("AP50          %.4f\n", s.ap);
    std::printf("precision     %.4f\n", s.precision);
    std::printf("recall        %.4f\n", s.recall);
    std::printf("ms per frame  %.2f (detector only)\n", ms);
    if (json) {
      const nlohmann::json j = {{"ap50", s.ap},         {"precision", s.precision}, {"recall", s.recall},
                                {"frames", s.frames},   {"ms_per_frame", ms},       {"ground_truth", s.ground_truth},
                                {"detections", s.detections}};
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& eval) {
  auto command = std::make_shared<EvalDetectCommand>();
  CLI::App* sub = eval.add_subcommand("detect", "Score people detection against ground truth (AP50, precision, recall)");
  sub->footer("Example: bodyrec eval detect --source /usr/share/doc/opencv-doc/examples/data/vtest.avi "
              "--gt ../shared/datasets/pets09_s2l1/PETS2009-S2L1.xml --json");
  add_source_options(*sub, command->source, true);
  sub->add_option("--gt", command->gt, "Ground truth: PETS/CVML XML (.xml) or MOTChallenge gt.txt")->required();
  sub->add_option("--iou", command->iou, "IoU a detection needs to match a ground-truth box")
      ->check(in_range(0.05, 1.0));
  sub->add_flag("--json", command->json, "End stdout with one JSON object (ap50, precision, recall, frames, ms_per_frame)");
  add_output_options(*sub, command->outputs);
  add_detector_options(*sub, command->detector);
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"eval", 10, add});

}  // namespace
}  // namespace bodyrec::cli
