// `bodyrec eval detect`: detection precision, recall and AP50 against PETS/CVML XML or MOT ground truth, or
// on the Penn-Fudan photos (ground truth from their instance masks).
#include <cstdio>
#include <iostream>
#include <map>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/eval/detection_metrics.h"
#include "bodyrec/io/ground_truth.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/io/pennfudan.h"
#include "command.h"
#include "common_options.h"
#include "detection_job.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

PennFudanSplit parse_split(const std::string& name) {
  if (name == "train") return PennFudanSplit::kTrain;
  if (name == "test") return PennFudanSplit::kTest;
  if (name == "all") return PennFudanSplit::kAll;
  throw UsageError("--split must be train, test or all (got '" + name + "')");
}

struct EvalDetectCommand {
  SourceOptions source;
  OutputOptions outputs;
  DetectorOptions detector;
  std::string gt, pennfudan, split = "test";
  double iou = 0.5;
  int bootstrap = 0;
  bool json = false;

  void run() const {
    std::unique_ptr<FrameSource> frames;
    std::map<int, std::vector<LabelledBox>> truth_by_frame;
    int truth_frames = 0;                  // frames the ground truth covers
    std::vector<PennFudanImage> photos;    // with --pennfudan: frame i is photos[i]
    if (!pennfudan.empty()) {
      if (!source.path.empty() || source.camera >= 0 || !gt.empty())
        throw UsageError("--pennfudan takes the images and the ground truth from DIR: no --source, --camera or --gt");
      if (detector.preset == DetectorPreset::kForeground)
        throw UsageError("--preset foreground needs one static camera's frames; --pennfudan's are unrelated photos");
      photos = load_pennfudan(pennfudan, parse_split(split));
      std::vector<std::string> files;
      for (size_t i = 0; i < photos.size(); ++i) {
        files.push_back(photos[i].image_path);
        auto& boxes = truth_by_frame[static_cast<int>(i)];
        for (const Box& b : photos[i].people) boxes.push_back({static_cast<int>(i), -1, b, 1.0, false});
      }
      truth_frames = static_cast<int>(photos.size());
      frames = open_image_list(files, "Penn-Fudan " + split + " split", source);
    } else {
      if (source.path.empty() && source.camera < 0) throw UsageError("eval detect needs --source VIDEO and --gt FILE, or --pennfudan DIR");
      if (gt.empty()) throw UsageError("eval detect --source needs --gt FILE");
      const GroundTruth truth = read_ground_truth(gt);
      truth_by_frame = truth.by_frame();
      truth_frames = truth.frame_count;
      frames = open_source(source);
    }
    auto people = make_detector(detector, *frames);
    DetectionEvaluator evaluator(iou);
    const std::vector<LabelledBox> none;
    const auto stats = run_detection(*frames, *people, outputs, !outputs.jsonl.empty(),
                                     [&](const Frame& frame, const std::vector<Detection>& detections) {
                                       if (frame.index >= truth_frames) return;  // beyond the ground truth
                                       if (!photos.empty()) {
                                         const PennFudanImage& photo = photos[static_cast<size_t>(frame.index)];
                                         if (frame.image.size() != photo.size)
                                           throw InputError(photo.mask_path + ": size differs from its image " +
                                                            photo.image_path);
                                       }
                                       const auto it = truth_by_frame.find(frame.index);
                                       evaluator.add_frame(detections, it == truth_by_frame.end() ? none : it->second);
                                     });
    const DetectionScores s = evaluator.scores();
    // No truth in the frames processed: a score of 0 would read as a detector that found nobody.
    if (s.ground_truth == 0 && photos.empty())
      throw InputError(gt + ": no ground-truth box in the " + std::to_string(stats.frames) +
                       " frames processed (is it this source's ground truth, and its frames?)");
    const double ms = stats.frames ? stats.detector_ms / stats.frames : 0.0;
    std::printf("detector      %s\n", people->describe().c_str());
    std::printf("frames        %d scored (of %d processed)\n", s.frames, stats.frames);
    std::printf("ground truth  %d boxes\n", s.ground_truth);
    std::printf("detections    %d (%d true, %d false at IoU >= %.2f)\n", s.detections, s.true_positives,
                s.false_positives, iou);
    std::printf("AP50          %.4f\n", s.ap);
    std::pair<double, double> interval{0, 0};
    if (bootstrap > 0) {
      interval = evaluator.ap_interval(bootstrap);
      std::printf("AP50 interval %.4f - %.4f (95 %%, bootstrap over the %d frames, %d draws)\n", interval.first,
                  interval.second, s.frames, bootstrap);
    }
    std::printf("precision     %.4f\n", s.precision);
    std::printf("recall        %.4f\n", s.recall);
    std::printf("ms per frame  %.2f (detector only)\n", ms);
    if (json) {
      nlohmann::json j = {{"ap50", s.ap},         {"precision", s.precision}, {"recall", s.recall},
                          {"frames", s.frames},   {"ms_per_frame", ms},       {"ground_truth", s.ground_truth},
                          {"detections", s.detections}};
      if (bootstrap > 0) {
        j["ap50_low"] = interval.first;
        j["ap50_high"] = interval.second;
      }
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& eval) {
  auto command = std::make_shared<EvalDetectCommand>();
  CLI::App* sub = eval.add_subcommand("detect", "Score people detection against ground truth (AP50, precision, recall)");
  sub->footer("Example: bodyrec eval detect --source /usr/share/doc/opencv-doc/examples/data/vtest.avi "
              "--gt ../shared/datasets/pets09_s2l1/PETS2009-S2L1.xml --json\n"
              "Photos: bodyrec eval detect --pennfudan ../shared/datasets/pennfudan --split test --preset photo "
              "--bootstrap 2000 --json\n"
              "Penn-Fudan ground truth: the tight box of each person's instance mask; the split is make-contour-set's "
              "(sorted names, every 4th image from the 4th is a test image).");
  add_source_options(*sub, command->source, true);
  CLI::Option* gt = sub->add_option("--gt", command->gt, "Ground truth: PETS/CVML XML (.xml) or MOTChallenge gt.txt");
  CLI::Option* pennfudan = sub->add_option(
      "--pennfudan", command->pennfudan,
      "Score on the Penn-Fudan photos in DIR (PNGImages/, PedMasks/) instead of --source and --gt");
  pennfudan->excludes(gt);
  sub->add_option("--split", command->split, "With --pennfudan: train, test or all")
      ->check(one_of({"train", "test", "all"}))
      ->needs(pennfudan)
      ->capture_default_str();
  sub->add_option("--iou", command->iou, "IoU a detection needs to match a ground-truth box")
      ->check(in_range(0.05, 1.0));
  sub->add_option("--bootstrap", command->bootstrap,
                  "Also give a 95 % interval of AP50 from this many bootstrap draws over the frames (0 = none; "
                  "meant for independent photos)")
      ->check(in_range(0, 100000));
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (ap50, precision, recall, frames, ms_per_frame; ap50_low and "
                "ap50_high with --bootstrap)");
  add_output_options(*sub, command->outputs);
  add_detector_options(*sub, command->detector, DetectorUse::kDetect);
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"eval", 10, add});

}  // namespace
}  // namespace bodyrec::cli
