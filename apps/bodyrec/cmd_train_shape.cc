// `bodyrec train-shape`: the 180-landmark body shape predictor (dlib regression-tree ensemble, thesis Ch3).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>

#include "bodyrec/core/error.h"
#include "bodyrec/landmarks/landmark_dataset.h"
#include "bodyrec/landmarks/landmark_metrics.h"
#include "bodyrec/landmarks/shape_training.h"
#include "command.h"
#include "output_check.h"
#include "landmark_report.h"

namespace bodyrec::cli {
namespace {

struct TrainShapeCommand {
  std::string train_xml, out;
  ShapeTrainOptions options;
  int holdout_every = 0;
  bool json = false;

  void run() const {
    if (holdout_every == 1) throw UsageError("--holdout-every must be 0 (off) or >= 2");
    require_output_folder(out);  // fail before a long training run, not after
    LandmarkDataset all = load_landmark_dataset(train_xml);
    if (all.landmarks == 0) throw InputError(train_xml + ": no box has landmarks (<part> elements)");
    LandmarkDataset train, validation;
    train.landmarks = validation.landmarks = all.landmarks;
    // Held out by source image: a mirrored copy (NAME_flip.png, from make-contour-set --flip) goes
    // wherever its original goes, so validation never sees a mirror of a training image.
    std::map<std::string, size_t> groups;
    for (auto& image : all.images) {
      std::string key = std::filesystem::path(image.path).stem().string();
      if (key.size() > 5 && key.compare(key.size() - 5, 5, "_flip") == 0) key.resize(key.size() - 5);
      const size_t group = groups.emplace(key, groups.size()).first->second;
      const bool held_out =
          holdout_every > 0 && group % static_cast<size_t>(holdout_every) == static_cast<size_t>(holdout_every - 1);
      (held_out ? validation : train).images.push_back(std::move(image));
    }
    const auto t0 = std::chrono::steady_clock::now();
    const BodyShapeModel model = train_body_shape(train, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    save_body_shape(model, out);
    std::printf("trained on    %d images, %d landmarks per person, %.1f s (%d threads)\n",
                static_cast<int>(train.images.size()), model.landmarks(), seconds, options.threads);
    const LandmarkScores t = evaluate_body_shape(model, train, train_xml);
    print_landmark_scores("training error", t);
    nlohmann::json j = {{"train", landmark_scores_json(t)}, {"seconds", seconds}};
    if (!validation.images.empty()) {
      const LandmarkScores v = evaluate_body_shape(model, validation, train_xml);
      print_landmark_scores("validation error (every " + std::to_string(holdout_every) + "th source image held out)", v);
      j["validation"] = landmark_scores_json(v);
    }
    const auto bytes = std::filesystem::file_size(out);
    std::printf("wrote         %s (%.1f MB)\n", out.c_str(), static_cast<double>(bytes) / 1e6);
    j["model_bytes"] = bytes;
    if (json) std::printf("%s\n", j.dump().c_str());
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<TrainShapeCommand>();
  CLI::App* sub = app.add_subcommand("train-shape", "Train the body-contour shape predictor from imglab landmarks");
  sub->footer(
      "The thesis used --oversampling 500 --nu 0.05 --tree-depth 2 and dlib's other defaults.\n"
      "Tuned on Penn-Fudan (docs/benchmarks.md): --oversampling 40 --trees-per-level 100.\n"
      "Example: bodyrec train-shape out/contours/train.xml --out out/shape.dat --oversampling 40 --trees-per-level 100");
  sub->add_option("train", command->train_xml, "Training set: imglab XML with numbered <part>s per box")->required();
  sub->add_option("--out", command->out, "Shape model file to write (dlib shape_predictor)")->required();
  auto& o = command->options;
  sub->add_option("--oversampling", o.oversampling, "Random initial shapes per person")->capture_default_str();
  sub->add_option("--nu", o.nu, "Learning rate (shrinkage)")->capture_default_str();
  sub->add_option("--tree-depth", o.tree_depth, "Depth of each regression tree")->capture_default_str();
  sub->add_option("--cascade-depth", o.cascade_depth, "Cascade levels")->capture_default_str();
  sub->add_option("--trees-per-level", o.trees_per_level, "Trees per cascade level")->capture_default_str();
  sub->add_option("--feature-pool-size", o.feature_pool_size, "Candidate pixels per cascade level")
      ->capture_default_str();
  sub->add_option("--test-splits", o.test_splits, "Random split tests tried per tree node")->capture_default_str();
  sub->add_option("--lambda", o.lambda, "Prior favouring nearby pixel pairs in split tests")->capture_default_str();
  sub->add_option("--padding", o.padding, "Grow the feature pool region by this fraction")->capture_default_str();
  sub->add_option("--threads", o.threads, "Training threads")->capture_default_str();
  sub->add_option("--seed", o.seed, "Random seed (default: dlib's fixed seed)");
  sub->add_option("--holdout-every", command->holdout_every,
                  "Hold out every Kth source image (index % K == K-1, mirrored copies with their original) for validation; 0 = none")
      ->capture_default_str();
  sub->add_flag("--verbose", o.verbose, "Print dlib's training progress");
  sub->add_flag("--json", command->json, "End stdout with one JSON object (train and validation errors)");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 32, add});

}  // namespace
}  // namespace bodyrec::cli
