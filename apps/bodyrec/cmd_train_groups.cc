// `bodyrec train-groups`: learns the pair model of group membership from walking-group scenes and prints
// it (or writes it to --out). The built-in models in src/bodyrec/groups/pair_model_builtin.cc are its
// output for each held-out scene and for all scenes.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "bodyrec/core/error.h"
#include "bodyrec/groups/group_eval.h"
#include "command.h"
#include "group_options.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

struct TrainGroupsCommand {
  std::vector<std::string> scenes;
  std::string out;
  std::vector<double> l2 = {0.01, 0.1, 1, 3};
  GroupCliOptions options;

  void run() const {
    const GroupOptions groups = options.resolved();
    std::vector<WalkingScene> loaded;
    for (const auto& dir : scenes) loaded.push_back(read_walking_scene(dir, options.seconds_per_frame));
    const double chosen = choose_l2(loaded, groups, l2);
    std::fprintf(stderr, "train-groups: L2 penalty %g\n", chosen);
    const std::string text = to_text(train_group_model(loaded, groups, chosen));
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
  CLI::App* sub = app.add_subcommand("train-groups", "Learn the pair model for group membership from labelled scenes");
  sub->footer("Example: bodyrec train-groups --scene ../shared/datasets/walking_groups/ETH/seq_hotel "
              "--scene ../shared/datasets/walking_groups/UCY/zara01 --out model.txt");
  sub->add_option("--scene", command->scenes, "Scene folder with obsmat.txt and groups.txt (repeat)")->required();
  sub->add_option("--out", command->out, "Model file to write (default: stdout)");
  sub->add_option("--l2", command->l2,
                  "L2 penalty on the standardised weights; with several values (and scenes), the one that does best "
                  "leave-one-scene-out within the training scenes")
      ->check(non_negative());
  add_group_options(*sub, command->options);
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 90, add});

}  // namespace
}  // namespace bodyrec::cli
