// `bodyrec train-detector`: a dlib fHOG people detector from the boxes of an imglab dataset (thesis Ch3).
#include <chrono>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/detection/fhog_training.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/landmarks/landmark_dataset.h"
#include "command.h"
#include "output_check.h"

namespace bodyrec::cli {
namespace {

std::vector<FhogTrainingImage> detector_images(const std::string& xml) {
  std::vector<FhogTrainingImage> out;
  for (auto& image : load_landmark_dataset(xml).images) {
    FhogTrainingImage t;
    t.image = image.image;
    for (const auto& person : image.people) (person.ignore ? t.ignore : t.boxes).push_back(person.box);
    out.push_back(std::move(t));
  }
  return out;
}

struct TrainDetectorCommand {
  std::string train_xml, test_xml, out;
  FhogTrainOptions options;
  bool json = false;

  void run() const {
    require_output_folder(out);  // fail before a long training run, not after
    const auto train = detector_images(train_xml);
    const auto test = test_xml.empty() ? std::vector<FhogTrainingImage>{} : detector_images(test_xml);
    const auto t0 = std::chrono::steady_clock::now();
    const FhogTrainReport report = train_fhog_detector(train, options, out);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("window        %dx%d (target size %d, median box aspect)\n", report.window.width,
                report.window.height, options.target_size);
    std::printf("boxes         %d trained on, %d the window cannot match ignored%s\n", report.boxes,
                report.unreachable, options.flip ? " (mirrored copies included)" : "");
    std::printf("training time %.1f s (%d threads)\n", seconds, options.threads);
    const DetectionAccuracy a = test_fhog_detector(out, train, options.upsample);
    std::printf("training      precision %.4f  recall %.4f  AP %.4f\n", a.precision, a.recall,
                a.average_precision);
    nlohmann::json j = {{"train_precision", a.precision}, {"train_recall", a.recall},
                        {"train_ap", a.average_precision}, {"seconds", seconds},
                        {"window", {report.window.width, report.window.height}},
                        {"boxes", report.boxes}, {"unreachable_boxes", report.unreachable}};
    if (!test.empty()) {
      const DetectionAccuracy t = test_fhog_detector(out, test, options.upsample);
      std::printf("test          precision %.4f  recall %.4f  AP %.4f (%s)\n", t.precision, t.recall,
                  t.average_precision, test_xml.c_str());
      j["test_precision"] = t.precision;
      j["test_recall"] = t.recall;
      j["test_ap"] = t.average_precision;
    }
    std::printf("wrote         %s%s\n", out.c_str(), options.upsample ? " (detect with --fhog-upsample 2)" : "");
    if (json) std::printf("%s\n", json_text(j).c_str());
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<TrainDetectorCommand>();
  CLI::App* sub = app.add_subcommand("train-detector", "Train a dlib fHOG + SVM people detector from imglab boxes");
  sub->footer(
      "Precision and recall count a detection as a hit at IoU >= 0.5 (dlib's test_object_detection_function).\n"
      "The thesis used -C 0.65 --epsilon 0.01 --target-size 100 --flip, no upsampling (on Penn-Fudan that finds\n"
      "nobody; -C 20 --target-size 64 --flip does better, see docs/benchmarks.md).\n"
      "Example: bodyrec train-detector out/boxes/train.xml --test out/boxes/test.xml --out out/detector.svm "
      "-C 20 --target-size 64 --flip");
  sub->add_option("train", command->train_xml, "Training set: imglab XML with boxes (ignore='1' boxes ignored)")
      ->required();
  sub->add_option("--out", command->out, "Detector file to write (.svm)")->required();
  sub->add_option("--test", command->test_xml, "Also report precision/recall on this imglab XML");
  auto& o = command->options;
  sub->add_option("-C,--svm-c", o.C, "SVM C: larger fits the training data harder")->capture_default_str();
  sub->add_option("--epsilon", o.epsilon, "Stop when the risk gap is below this")->capture_default_str();
  sub->add_option("--target-size", o.target_size, "Sliding window area = SIZE x SIZE pixels")
      ->capture_default_str();
  sub->add_flag("--upsample", o.upsample, "Train on 2x upsampled images (finds smaller people)");
  sub->add_flag("--flip", o.flip, "Add left-right mirrored training images");
  sub->add_option("--threads", o.threads, "Training threads")->capture_default_str();
  sub->add_flag("--verbose", o.verbose, "Print dlib's optimiser progress");
  sub->add_flag("--json", command->json, "End stdout with one JSON object (train/test precision, recall, AP)");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 31, add});

}  // namespace
}  // namespace bodyrec::cli
