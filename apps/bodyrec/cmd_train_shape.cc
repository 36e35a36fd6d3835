// `bodyrec train-shape`: the 180-landmark body shape model: the per-pixel body mask network (default) or
// the thesis's dlib regression-tree ensemble (Ch3).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "bodyrec/core/error.h"
#include "bodyrec/core/openblas.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/landmarks/landmark_dataset.h"
#include "bodyrec/landmarks/landmark_metrics.h"
#include "bodyrec/landmarks/shape_training.h"
#include "command.h"
#include "enum_option.h"
#include "output_check.h"
#include "landmark_report.h"

namespace bodyrec::cli {
namespace {

struct TrainShapeCommand {
  std::string train_xml, out;
  ShapeTrainOptions options;
  int holdout_every = 0;
  std::string net_size = "24x72", seed, holdout_xml;
  bool json = false;
  std::vector<const CLI::Option*> net_only, trees_only;  // options one method reads and the other would ignore

  void run() {
    if (holdout_every == 1) throw UsageError("--holdout-every must be 0 (off) or >= 2");
    const bool net = options.method == ShapeMethod::kMaskNet;
    for (const CLI::Option* option : net ? trees_only : net_only)
      if (option->count() > 0)
        throw UsageError(option->get_name() + " is a " + (net ? "trees" : "mask-net") + " option; --method " +
                         (net ? "mask-net" : "trees") + " takes none");
    parse_net_options();
    options.check();
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
    if (!holdout_xml.empty()) {
      if (validation.images.empty()) throw UsageError("--holdout-xml needs --holdout-every K");
      write_landmark_dataset(validation, holdout_xml, "validation part of " + train_xml);
    }
    const auto t0 = std::chrono::steady_clock::now();
    const BodyShapeModel model = train_body_shape(train, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    save_body_shape(model, out);
    const std::string blas = openblas_core();
    const std::string kernels = blas.empty() ? "" : " (OpenBLAS kernels: " + blas + ")";
    std::printf("trained on    %d images, %d landmarks per person, %s, %.1f s%s\n", static_cast<int>(train.images.size()),
                model.landmarks(), model.kind_name().c_str(), seconds, kernels.c_str());
    const LandmarkScores t = evaluate_body_shape(model, train, train_xml);
    print_landmark_scores("training error", t);
    nlohmann::json j = {{"train", landmark_scores_json(t)}, {"seconds", seconds}, {"method", model.kind_name()}};
    if (!blas.empty()) j["blas_kernels"] = blas;
    if (!validation.images.empty()) {
      const LandmarkScores v = evaluate_body_shape(model, validation, train_xml);
      print_landmark_scores("validation error (every " + std::to_string(holdout_every) + "th source image held out)", v);
      j["validation"] = landmark_scores_json(v);
    }
    const auto bytes = std::filesystem::file_size(out);
    std::printf("wrote         %s (%.1f MB)\n", out.c_str(), static_cast<double>(bytes) / 1e6);
    j["model_bytes"] = bytes;
    if (json) std::printf("%s\n", json_text(j).c_str());
  }

  // --net-size WxH and --seed (text for dlib's trees, an integer for the network's augmentation draws).
  void parse_net_options() {
    const auto x = net_size.find('x');
    const auto whole_int = [](const std::string& s, int& value) {
      if (s.empty() || s.size() > 5 || s.find_first_not_of("0123456789") != std::string::npos) return false;
      value = std::stoi(s);
      return true;
    };
    if (x == std::string::npos || !whole_int(net_size.substr(0, x), options.net.input_width) ||
        !whole_int(net_size.substr(x + 1), options.net.input_height))
      throw UsageError("--net-size must be WxH, e.g. 32x96 (got '" + net_size + "')");
    options.seed = seed;
    if (options.method == ShapeMethod::kMaskNet && !seed.empty()) {
      if (seed.size() > 9 || seed.find_first_not_of("0123456789") != std::string::npos)
        throw UsageError("--seed must be a whole number below 10^9 with --method mask-net (got '" + seed + "')");
      options.net.seed = static_cast<unsigned>(std::stoul(seed));
    }
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<TrainShapeCommand>();
  CLI::App* sub = app.add_subcommand("train-shape", "Train the body-contour shape model from imglab landmarks");
  sub->footer(
      "mask-net (default): a small U-Net labels each pixel of the box as body or not; the landmarks are that\n"
      "mask's outline, numbered like the training contours (point 0 at the head top, clockwise, equal arc\n"
      "length), each then moved along it by its mean offset on the training people (stored in the model);\n"
      "fitting thresholds the mean of the network's logits on the box and on its mirror image (eval landmarks\n"
      "--no-mirror), cuts a slit between the legs where the logits dip (--no-leg-slit), averages each\n"
      "landmark over the outlines at five thresholds (--threshold-offsets), then applies a linear\n"
      "correction of the whole shape learnt on the training people's fits (ridge regression, stored in\n"
      "the model; eval landmarks --no-correction). Its target masks are the filled\n"
      "landmark polygons. dlib trains the network, its convolutions computed by oneDNN, one thread per\n"
      "network. --networks 2 (the default) trains two networks side by side and fitting averages their\n"
      "logits (the shipped pair: 5.98 % of box height on the Penn-Fudan test split), for 1.4x the fitting\n"
      "time of one (docs/benchmarks.md). trees: the thesis's\n"
      "dlib regression trees; the thesis used --oversampling 500 --nu 0.05 --tree-depth 2 and dlib's other\n"
      "defaults; tuned on Penn-Fudan: --oversampling 40 --trees-per-level 100. Figures for both:\n"
      "docs/benchmarks.md.\n"
      "Example: bodyrec train-shape out/contours/train.xml --out out/shape.dat\n"
      "         bodyrec train-shape out/contours/train.xml --out out/trees.dat --method trees --oversampling 40 --trees-per-level 100");
  sub->add_option("train", command->train_xml, "Training set: imglab XML with numbered <part>s per box")->required();
  sub->add_option("--out", command->out, "Shape model file to write")->required();
  auto& o = command->options;
  add_enum_option(*sub, "--method", o.method,
                  std::vector<std::pair<std::string, ShapeMethod>>{{"mask-net", ShapeMethod::kMaskNet},
                                                                   {"trees", ShapeMethod::kTrees}},
                  "mask-net (per-pixel body mask, then its outline) or trees (the thesis's)", "mask-net");
  sub->add_option("--net-size", command->net_size, "mask-net: the box is resampled to WxH (multiples of 8)")
      ->capture_default_str();
  sub->add_option("--iterations", o.net.iterations, "mask-net: training mini-batches")->capture_default_str();
  sub->add_option("--batch", o.net.batch, "mask-net: crops per mini-batch")->capture_default_str();
  sub->add_option("--learning-rate", o.net.learning_rate, "mask-net: peak learning rate (Adam; warm-up, then cosine)")
      ->capture_default_str();
  sub->add_option("--weight-decay", o.net.weight_decay, "mask-net: L2 penalty on the weights (Adam's)")
      ->capture_default_str();
  sub->add_option("--mask-threshold", o.net.threshold, "mask-net: logit above which a pixel is body (kept in the model)")
      ->capture_default_str();
  sub->add_option("--box-jitter", o.net.box_jitter, "mask-net: std-dev of random box shifts and size changes (fraction)")
      ->capture_default_str();
  sub->add_option("--networks", o.net.networks,
                  "mask-net: networks trained side by side (seeds S, S+1, ...); fitting averages their logits")
      ->capture_default_str();
  sub->add_option("--oversampling", o.oversampling, "trees: random initial shapes per person")->capture_default_str();
  sub->add_option("--nu", o.nu, "trees: learning rate (shrinkage)")->capture_default_str();
  sub->add_option("--tree-depth", o.tree_depth, "trees: depth of each regression tree")->capture_default_str();
  sub->add_option("--cascade-depth", o.cascade_depth, "trees: cascade levels")->capture_default_str();
  sub->add_option("--trees-per-level", o.trees_per_level, "trees: trees per cascade level")->capture_default_str();
  sub->add_option("--feature-pool-size", o.feature_pool_size, "trees: candidate pixels per cascade level")
      ->capture_default_str();
  sub->add_option("--test-splits", o.test_splits, "trees: random split tests tried per tree node")->capture_default_str();
  sub->add_option("--lambda", o.lambda, "trees: prior favouring nearby pixel pairs in split tests")->capture_default_str();
  sub->add_option("--padding", o.padding, "trees: grow the feature pool region by this fraction")->capture_default_str();
  sub->add_option("--threads", o.threads, "trees: training threads")->capture_default_str();
  for (const char* name : {"--net-size", "--iterations", "--batch", "--learning-rate", "--weight-decay",
                           "--mask-threshold", "--box-jitter", "--networks"})
    command->net_only.push_back(sub->get_option(name));
  for (const char* name : {"--oversampling", "--nu", "--tree-depth", "--cascade-depth", "--trees-per-level",
                           "--feature-pool-size", "--test-splits", "--lambda", "--padding", "--threads"})
    command->trees_only.push_back(sub->get_option(name));
  sub->add_option("--seed", command->seed,
                  "Random seed (trees: any text, default dlib's fixed seed; mask-net: a whole number, default 0)");
  sub->add_option("--holdout-every", command->holdout_every,
                  "Hold out every Kth source image (index % K == K-1, mirrored copies with their original) for validation; 0 = none")
      ->capture_default_str();
  sub->add_option("--holdout-xml", command->holdout_xml,
                  "Write the held-out images as imglab XML (absolute image paths), to score them again with "
                  "`eval landmarks`");
  sub->add_flag("--verbose", o.verbose, "Print training progress");
  sub->add_flag("--json", command->json, "End stdout with one JSON object (train and validation errors)");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 32, add});

}  // namespace
}  // namespace bodyrec::cli
