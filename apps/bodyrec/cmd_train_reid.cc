// `bodyrec train-reid`: learns the XQDA metric of the default re-identification matcher from labelled
// two-camera images and writes it as a model file (cv::FileStorage YAML).
#include <cstdio>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/appearance_matcher.h"
#include "bodyrec/reid/reid_eval.h"
#include "command.h"
#include "reid_dataset_options.h"

namespace bodyrec::cli {
namespace {

struct TrainReidCommand {
  ReidDatasetOptions dataset;
  std::string out, matcher_name = "default";

  void run() const {
    auto matcher = make_untrained_matcher(matcher_name);
    if (!matcher->learns()) throw UsageError("matcher " + matcher_name + " learns nothing (use default, default-full or lomo-xqda)");
    const ReidDataset data = scan_reid_dataset(dataset.root, dataset.id_regex, dataset.cam_regex);
    const std::vector<std::vector<float>> features = dataset_features(data, *matcher);
    std::vector<TrainingSample> samples;
    for (size_t i = 0; i < data.images.size(); ++i)
      samples.push_back({&features[i], data.images[i].identity, data.images[i].camera});
    matcher->train(samples);
    matcher->save_model(out);
    std::fprintf(stderr, "train-reid: %zu images, %zu identities (%zu in both cameras) -> %s\n%s\n",
                 data.images.size(), data.identities.size(), data.in_both.size(), out.c_str(), matcher->summary().c_str());
  }
};
void add(CLI::App& app) {
  auto command = std::make_shared<TrainReidCommand>();
  CLI::App* sub = app.add_subcommand(
      "train-reid", "Learn the re-identification metric (LOMO/GOG + XQDA) from labelled images of two cameras");
  sub->footer(
      "Every image matching both regexes is used; same-person pairs are the two cameras' images of one "
      "identity. The default matchers first pick their variant by cross-validation over these people; default-full (the "
      "same on the unsketched features, up to 100 dimensions per part) is more accurate and its model about "
      "7.7 MB, against 1 MB. Use the "
      "model with `--model FILE` (reid, eval reid, eval reid-stream), or put a default model in models/ as "
      "reid-default.yml.gz (or in $BODYREC_MODELS) to replace the shipped one.\n"
      "Example: bodyrec train-reid --root my_people --id-regex '^(\\w+)/' --cam-regex '/cam(\\d)_' --out reid.yml.gz");
  add_reid_dataset_options(*sub, command->dataset);
  sub->add_option("--matcher", command->matcher_name, "default | default-full | lomo-xqda")->capture_default_str();
  sub->add_option("--out", command->out, "Model file to write (.yml, or .yml.gz compressed)")->required();
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 92, add});

}  // namespace
}  // namespace bodyrec::cli
