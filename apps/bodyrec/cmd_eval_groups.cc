// `bodyrec eval groups`: trajectory-based group membership scored on a walking-group scene (EWAP/UCY
// obsmat.txt + groups.txt): pair precision, recall and F1 over the pairs of people seen at the same time.
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/groups/group_eval.h"
#include "bodyrec/io/json_numbers.h"
#include "command.h"
#include "group_options.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

struct EvalGroupsCommand {
  std::string scene_dir;
  std::string method = "learned";
  std::string model = "auto";
  GroupCliOptions options;
  double max_distance = 2.0;
  double max_speed_difference = 0.4;
  bool json = false;

  void run() const {
    GroupOptions groups = options.resolved();
    if (method != "learned" && method != "threshold")
      throw UsageError("--method must be learned or threshold, got '" + method + "'");
    const WalkingScene scene = read_walking_scene(scene_dir, options.seconds_per_frame);
    std::string model_name;
    PairScores s;
    if (method == "threshold") {
      s = evaluate_threshold(scene, max_distance, max_speed_difference, groups.velocity_span_s);
      char rule[96];
      std::snprintf(rule, sizeof rule, "median distance <= %g m and median speed difference <= %g m/s",
                    max_distance, max_speed_difference);
      model_name = rule;
    } else {
      groups.model = model == "auto" ? std::make_shared<const PairModel>(builtin_pair_model_for(scene.name))
                                     : std::make_shared<const PairModel>(read_pair_model(model));
      model_name = "logistic regression trained on";
      for (const auto& name : groups.model->trained_on) model_name += " " + name;
      if (groups.model->trained_on_scene(scene.name)) model_name += " (includes this scene)";
      s = evaluate_learned(scene, replay_evidence(scene, groups), groups.linkage);
    }
    std::printf("scene           %s (%zu rows, %.4f s per frame)\n", scene.name.c_str(), scene.rows.size(),
                scene.seconds_per_frame);
    std::printf("method          %s: %s\n", method.c_str(), model_name.c_str());
    std::printf("pairs           %d seen together in a frame, %d labelled together, %d predicted\n", s.pairs,
                s.labelled_pairs, s.predicted_pairs);
    std::printf("pair precision  %.4f\n", s.precision);
    std::printf("pair recall     %.4f\n", s.recall);
    std::printf("pair F1         %.4f\n", s.f1);
    if (json) {
      const nlohmann::json j = {{"pair_precision", s.precision}, {"pair_recall", s.recall},
                                {"pair_f1", s.f1},               {"pairs", s.pairs},
                                {"labelled_pairs", s.labelled_pairs}, {"predicted_pairs", s.predicted_pairs},
                                {"true_pairs", s.true_pairs},    {"scene", scene.name},
                                {"method", method},              {"model", model_name}};
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& eval) {
  auto command = std::make_shared<EvalGroupsCommand>();
  CLI::App* sub = eval.add_subcommand(
      "groups", "Score group membership from trajectories on an EWAP/UCY scene (pair precision, recall, F1)");
  sub->footer("Example: bodyrec eval groups --scene ../shared/datasets/walking_groups/ETH/seq_hotel --json\n"
              "With --model auto a scene the built-in models were trained on is scored with the model trained\n"
              "on the other scenes only (leave-one-scene-out).");
  sub->add_option("--scene", command->scene_dir, "Scene folder with obsmat.txt and groups.txt")->required();
  sub->add_option("--method", command->method, "learned (pair model + group consistency) or threshold (plain rule)");
  sub->add_option("--model", command->model,
                  "auto (built-in, never trained on this scene) or a model file from `bodyrec train-groups`");
  sub->add_option("--max-distance", command->max_distance, "threshold method: median distance limit (m)")
      ->check(positive());
  sub->add_option("--max-speed-difference", command->max_speed_difference,
                  "threshold method: median speed difference limit (m/s)")
      ->check(non_negative());
  add_group_options(*sub, command->options);
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (pair_precision, pair_recall, pair_f1, pairs, ...)");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"eval", 40, add});

}  // namespace
}  // namespace bodyrec::cli
