// `bodyrec eval groups`: trajectory-based group membership scored on walking-group scenes (EWAP/UCY
// obsmat.txt + groups.txt): pair precision, recall and F1 over the pairs of people seen at the same time;
// with --nested, every method family scored by nested leave-one-scene-out.
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/groups/group_selection.h"
#include "bodyrec/io/json_numbers.h"
#include "command.h"
#include "enum_option.h"
#include "group_options.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

enum class EvalMethod { kLearned, kThreshold };

nlohmann::json scores_json(const PairScores& s) {
  return {{"pair_precision", s.precision}, {"pair_recall", s.recall},   {"pair_f1", s.f1},
          {"pairs", s.pairs},              {"labelled_pairs", s.labelled_pairs},
          {"predicted_pairs", s.predicted_pairs}, {"true_pairs", s.true_pairs}};
}

struct EvalGroupsCommand {
  std::vector<std::string> scene_dirs;
  EvalMethod method = EvalMethod::kLearned;
  std::string model = "auto";
  GroupCliOptions options;
  double max_distance = 2.0;
  double max_speed_difference = 0.4;
  bool baseline = false;
  bool nested = false;
  bool json = false;

  // The rule of --method threshold (and of --baseline: the plain rule, linkage none).
  GroupCandidate rule(bool plain) const {
    GroupCandidate c;
    c.method = GroupMethod::kRule;
    c.linkage = GroupLinkage::kNone;
    if (!plain) {
      c.max_distance_m = max_distance;
      c.max_speed_difference = max_speed_difference;
      if (options.linkage_given()) c.linkage = options.linkage_value();
    }
    return c;
  }

  void run() const {
    const EvalMethod m = method;
    std::vector<WalkingScene> scenes;
    for (const auto& dir : scene_dirs) scenes.push_back(read_walking_scene(dir, options.seconds_per_frame));
    if (nested) return run_nested(std::move(scenes));

    nlohmann::json results = nlohmann::json::array();
    double sum = 0, baseline_sum = 0;
    for (const auto& scene : scenes) {
      std::printf("scene           %s (%zu rows, %.4f s per frame)\n", scene.name.c_str(), scene.rows.size(),
                  scene.seconds_per_frame);
      PairScores s;
      std::string name;
      if (m == EvalMethod::kThreshold) {
        const GroupCandidate c = rule(false);
        GroupSelection selection({scene}, options.velocity_span());
        s = selection.score(selection.fit(c, {0}), 0);
        name = describe(c);
      } else {
        auto pair_model = model == "auto" ? std::make_shared<const PairModel>(builtin_pair_model_for(scene.name))
                                          : std::make_shared<const PairModel>(read_pair_model(model));
        const GroupOptions groups = options.resolved(pair_model);
        PairModel used = *pair_model;  // described with the settings that apply
        used.window_s = groups.window_s;
        used.min_moving_fraction = groups.min_moving_fraction;
        used.linkage = groups.linkage;
        name = describe(used) + "; trained on";
        for (const auto& trained : pair_model->trained_on) name += " " + trained;
        if (pair_model->trained_on_scene(scene.name)) name += " (includes this scene)";
        s = evaluate_learned(scene, replay_evidence(scene, groups), groups.linkage);
      }
      std::printf("method          %s\n", name.c_str());
      std::printf("pairs           %d seen together in a frame, %d labelled together, %d predicted\n", s.pairs,
                  s.labelled_pairs, s.predicted_pairs);
      std::printf("pair precision  %.4f\n", s.precision);
      std::printf("pair recall     %.4f\n", s.recall);
      std::printf("pair F1         %.4f\n", s.f1);
      nlohmann::json j = scores_json(s);
      j["scene"] = scene.name;
      j["method"] = m == EvalMethod::kThreshold ? "threshold" : "learned";
      j["model"] = name;
      sum += s.f1;
      if (baseline) {
        const GroupCandidate c = rule(true);
        GroupSelection selection({scene}, options.velocity_span());
        const PairScores b = selection.score(selection.fit(c, {0}), 0);
        std::printf("baseline        %s: precision %.4f recall %.4f F1 %.4f (%d predicted)\n", describe(c).c_str(),
                    b.precision, b.recall, b.f1, b.predicted_pairs);
        j["baseline"] = scores_json(b);
        j["baseline"]["method"] = describe(c);
        baseline_sum += b.f1;
      }
      results.push_back(j);
    }
    const double n = static_cast<double>(scenes.size());
    if (scenes.size() > 1) {
      std::printf("mean pair F1    %.4f over %zu scenes", sum / n, scenes.size());
      if (baseline) std::printf(" (baseline %.4f)", baseline_sum / n);
      std::printf("\n");
    }
    if (!json) return;
    if (scenes.size() == 1) {
      std::printf("%s\n", json_text(results[0]).c_str());
    } else {
      nlohmann::json j = {{"scenes", results}, {"mean_pair_f1", sum / n}};
      if (baseline) j["baseline_mean_pair_f1"] = baseline_sum / n;
      std::printf("%s\n", json_text(j).c_str());
    }
  }

  void run_nested(std::vector<WalkingScene> scenes) const {
    if (scenes.size() < 3)
      throw UsageError("--nested needs at least 3 --scene folders (one held out, two to choose by), got " +
                       std::to_string(scenes.size()));
    GroupSelection selection(std::move(scenes), options.velocity_span());
    const auto& all = selection.scenes();
    std::printf("nested leave-one-scene-out: each scene scored by the method whose settings were chosen by\n"
                "leave-one-scene-out within the other scenes and then fitted on them; pair F1 (precision / recall)\n");
    std::printf("%-58s", "method");
    for (const auto& s : all) std::printf(" %-22s", s.name.c_str());
    std::printf(" mean\n");
    nlohmann::json methods = nlohmann::json::array();
    std::vector<NestedResult> results;
    for (const auto& family : standard_group_families()) {
      const NestedResult r = selection.nested_loso(family);
      std::printf("%-58s", family.name.c_str());
      nlohmann::json folds = nlohmann::json::array();
      for (const auto& f : r.folds) {
        char cell[64];
        std::snprintf(cell, sizeof cell, "%.4f (%.3f / %.3f)", f.scores.f1, f.scores.precision, f.scores.recall);
        std::printf(" %-22s", cell);
        nlohmann::json j = scores_json(f.scores);
        j["scene"] = f.scene;
        j["chosen"] = f.fitted;
        j["inner_f1"] = f.inner_f1;
        folds.push_back(j);
      }
      std::printf(" %.4f\n", r.mean_f1);
      std::fflush(stdout);
      methods.push_back({{"method", r.family}, {"scenes", folds}, {"mean_pair_f1", r.mean_f1}});
      results.push_back(r);
    }
    std::printf("settings chosen within the training scenes (inner leave-one-scene-out F1):\n");
    for (const auto& r : results) {
      std::printf("  %s\n", r.family.c_str());
      for (const auto& f : r.folds)
        std::printf("    %-10s %s (%.4f)\n", f.scene.c_str(), f.fitted.c_str(), f.inner_f1);
    }
    if (json) std::printf("%s\n", json_text({{"protocol", "nested-loso"}, {"methods", methods}}).c_str());
  }
};

void add(CLI::App& eval) {
  auto command = std::make_shared<EvalGroupsCommand>();
  CLI::App* sub = eval.add_subcommand(
      "groups", "Score group membership from trajectories on EWAP/UCY scenes (pair precision, recall, F1)");
  sub->footer(
      "Examples:\n"
      "  bodyrec eval groups --scene ../shared/datasets/walking_groups/ETH/seq_hotel --baseline --json\n"
      "  bodyrec eval groups --nested --scene DIR1 --scene DIR2 --scene DIR3\n"
      "With --model auto a scene the built-in models were trained on is scored with the model trained\n"
      "on the other scenes only.");
  sub->add_option("--scene", command->scene_dirs, "Scene folder with obsmat.txt and groups.txt (repeat for several)")
      ->required();
  add_enum_option(*sub, "--method", command->method,
                  std::vector<std::pair<std::string, EvalMethod>>{{"learned", EvalMethod::kLearned},
                                                                  {"threshold", EvalMethod::kThreshold}},
                  "learned (the model of --model: by default the built-in learned rule) or threshold (the rule "
                  "with --max-distance and --max-speed-difference over the pair's whole common time; "
                  "--linkage applies if given, else none)",
                  "learned");
  sub->add_option("--model", command->model,
                  "auto (built-in, never trained on this scene) or a model file from `bodyrec train-groups`; "
                  "its window, min-moving share and linkage apply unless given");
  sub->add_option("--max-distance", command->max_distance, "threshold method: median distance limit (m)")
      ->check(positive());
  sub->add_option("--max-speed-difference", command->max_speed_difference,
                  "threshold method: median speed difference limit (m/s)")
      ->check(non_negative());
  sub->add_flag("--baseline", command->baseline,
                "Also score the plain rule (median distance <= 2 m and median speed difference <= 0.4 m/s over "
                "the pair's common frames, no group consistency) on each scene");
  sub->add_flag("--nested", command->nested,
                "Nested leave-one-scene-out over the 3+ scenes: every method family (rules, pair models; "
                "linkage none, single, chosen) with its settings chosen within the other scenes only");
  add_group_options(*sub, command->options, GroupInput::kSceneFiles);
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (pair_precision, pair_recall, pair_f1, pairs, ...)");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"eval", 40, add});

}  // namespace
}  // namespace bodyrec::cli
