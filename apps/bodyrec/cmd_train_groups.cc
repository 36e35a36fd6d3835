// `bodyrec train-groups`: chooses and fits the pair model of group membership on labelled walking-group
// scenes and prints it (or writes it to --out). The built-in models in
// src/bodyrec/groups/pair_model_builtin.cc are its output for each held-out scene and for all scenes.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "bodyrec/core/error.h"
#include "bodyrec/groups/group_selection.h"
#include "command.h"
#include "enum_option.h"
#include "group_options.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

enum class TrainMethod { kRule, kPairModel };
enum class TrainFeatures { kAll, kDistanceSpeed };

struct TrainGroupsCommand {
  std::vector<std::string> scenes;
  std::string out;
  TrainMethod method = TrainMethod::kRule;
  TrainFeatures features = TrainFeatures::kAll;
  std::vector<double> l2 = {0.01, 0.1, 1, 3, 10};
  GroupCliOptions options;

  GroupFamily family() const {
    const TrainMethod m = method;
    const PairFeatureSet set = features == TrainFeatures::kAll ? all_pair_features() : distance_speed_features();

    const double whole = std::numeric_limits<double>::infinity();
    std::vector<double> windows = m == TrainMethod::kRule ? std::vector<double>{whole} : std::vector<double>{8, 5, 12};
    std::vector<double> moving = {0.5, 0};
    std::vector<GroupLinkage> linkages = linkage_grid();
    std::vector<double> spans = velocity_span_grid();
    if (options.window_given()) windows = {options.groups.window_s};
    if (options.min_moving_given()) moving = {options.groups.min_moving_fraction};
    if (options.linkage_given()) linkages = {options.linkage_value()};
    if (options.velocity_span_given()) spans = {options.groups.velocity_span_s};
    const GroupGrid grid{linkages, windows, moving, spans};
    return m == TrainMethod::kRule ? learned_rule_family("learned rule", grid)
                                   : pair_model_family("pair model", set, l2, grid);
  }

  void run() const {
    const GroupFamily grid = family();
    std::vector<WalkingScene> loaded;
    for (const auto& dir : scenes) loaded.push_back(read_walking_scene(dir, options.seconds_per_frame));
    GroupSelection selection(std::move(loaded), options.velocity_span());
    std::vector<size_t> all;
    for (size_t s = 0; s < selection.scenes().size(); ++s) all.push_back(s);
    double inner = 0;
    const GroupCandidate chosen = selection.choose(grid, all, &inner);
    const FittedGroupMethod& fitted = selection.fit(chosen, all);
    if (all.size() >= 2 && grid.grid.size() > 1)
      std::fprintf(stderr, "train-groups: %s (leave-one-scene-out F1 %.4f within these scenes)\n",
                   describe(fitted).c_str(), inner);
    else
      std::fprintf(stderr, "train-groups: %s (the first of the grid: nothing to choose by)\n", describe(fitted).c_str());
    const std::string text = to_text(*fitted.model);
    if (out.empty()) {
      std::printf("%s", text.c_str());
      return;
    }
    std::ofstream file(out);
    file << text;
    if (!file.flush()) throw ProcessingError(out + ": cannot write the model");
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<TrainGroupsCommand>();
  CLI::App* sub = app.add_subcommand(
      "train-groups", "Choose and fit the group-membership model on labelled scenes (as the built-in models are made)");
  sub->footer(
      "Example: bodyrec train-groups --scene ../shared/datasets/walking_groups/ETH/seq_hotel "
      "--scene ../shared/datasets/walking_groups/UCY/zara01 --out model.txt\n"
      "Settings not given (window, min-moving share, linkage, L2 penalty) are chosen by leave-one-scene-out\n"
      "within the given scenes (with one scene: the first of each list); thresholds and weights are then\n"
      "fitted on all of them.");
  sub->add_option("--scene", command->scenes, "Scene folder with obsmat.txt and groups.txt (repeat)")->required();
  sub->add_option("--out", command->out, "Model file to write (default: stdout)");
  add_enum_option(*sub, "--method", command->method,
                  std::vector<std::pair<std::string, TrainMethod>>{{"rule", TrainMethod::kRule},
                                                                   {"pair-model", TrainMethod::kPairModel}},
                  "rule (median distance and speed difference thresholds over the pair's common time, "
                  "learned) or pair-model (logistic regression over --window seconds)",
                  "rule");
  add_enum_option(*sub, "--features", command->features,
                  std::vector<std::pair<std::string, TrainFeatures>>{{"all", TrainFeatures::kAll},
                                                                     {"distance-speed", TrainFeatures::kDistanceSpeed}},
                  "pair-model: all features or only median distance and speed difference", "all");
  sub->add_option("--l2", command->l2, "pair-model: L2 penalties to choose from (on the standardised weights)")
      ->check(non_negative());
  add_group_options(*sub, command->options, GroupInput::kSceneFiles);
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 90, add});

}  // namespace
}  // namespace bodyrec::cli
