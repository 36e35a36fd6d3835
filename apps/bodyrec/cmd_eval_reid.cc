// `bodyrec eval reid`: CMC and mAP of an appearance matcher on a two-camera re-identification set
// (VIPeR protocol: random splits into training and test identities).
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/core/model_files.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/reid/appearance_matcher.h"
#include "bodyrec/reid/learned_matcher.h"
#include "bodyrec/reid/reid_eval.h"
#include "command.h"
#include "reid_dataset_options.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

struct EvalReidCommand {
  ReidDatasetOptions dataset;
  ReidEvalOptions eval;
  std::string matcher = "default";
  std::string model, resize;
  bool json = false;

  void run() {
    // Unknown name, unreadable model or bad option: fail before reading images. Without --model a
    // learning matcher is trained on each split's training people (never on its test people); with
    // --train-ids 0 there are none, and the default matcher uses its shipped model (models/README.md).
    if (!resize.empty()) eval.resize = parse_image_size(resize, "--resize");
    eval.check();
    const bool learn = model.empty() && make_untrained_matcher(matcher)->learns() && eval.train_ids != 0;
    if (model.empty() && !learn && (matcher == "lomo-xqda" || matcher == "default-full"))
      throw UsageError("matcher " + matcher + " learns: give --train-ids > 0 or --model");
    if (!learn) (void)make_matcher(matcher, model);
    if (!learn && model.empty() && make_untrained_matcher(matcher)->learns())
      std::fprintf(stderr,
                   "bodyrec: note: %s is used as is on every person; the shipped one was trained on all 632 VIPeR "
                   "people (models/README.md), so on VIPeR this scores its own training data, not accuracy: "
                   "--train-ids N trains on each split's training people instead\n",
                   find_model_file(kShippedReidModel).value_or(kShippedReidModel).c_str());
    const ReidDataset data = scan_reid_dataset(dataset.root, dataset.id_regex, dataset.cam_regex);
    eval.learn = learn;  // a given or shipped model is used as is in every split
    const std::string name = matcher, model_path = model;
    const ReidEvalResult r = evaluate_reid(
        data, [&] { return learn ? make_untrained_matcher(name) : make_matcher(name, model_path); }, eval);
    const int probe_camera = eval.swap_cameras ? 1 : 0;
    std::printf("matcher       %s\n", r.matcher.c_str());
    std::printf("images        %zu (%zu identities, %zu in both cameras; cameras '%s' -> '%s'; %d files skipped)%s\n",
                data.images.size(), data.identities.size(), data.in_both.size(),
                data.cameras[probe_camera].c_str(), data.cameras[1 - probe_camera].c_str(), data.skipped,
                eval.resize.empty() ? "" : (", resampled to " + resize).c_str());
    std::printf("splits        %d (seed %u), %d training identities, %d probes, %d gallery images\n", eval.splits,
                eval.seed, r.train_ids, r.probes, r.gallery);
    std::printf("CMC           rank-1 %.2f %%  rank-5 %.2f %%  rank-10 %.2f %%  rank-20 %.2f %%\n", 100 * r.rank1,
                100 * r.rank5, 100 * r.rank10, 100 * r.rank20);
    std::printf("mAP           %.2f %%\n", 100 * r.map);
    if (learn)
      for (size_t s = 0; s < r.rank1_per_split.size(); ++s)
        std::printf("split %-7zu rank-1 %.2f %%  mAP %.2f %%  %s\n", s, 100 * r.rank1_per_split[s],
                    100 * r.map_per_split[s], r.matcher_per_split[s].c_str());
    std::printf("threshold     accepts %.1f %% of same-person pairs, rejects %.1f %% of different-person pairs\n",
                100 * r.same_accepted, 100 * r.different_rejected);
    std::printf("ms per image  %.2f (features + descriptor + matching, training excluded)\n", r.ms_per_image);
    const OpenSetScores& o = r.open_set;
    if (eval.open_set) {
      std::printf("open set      %d enrolled probes, %d strangers per split; DIR at FAR 1 %% %.3f, at FAR 10 %% %.3f; "
                  "rank-1 among the enrolled %.2f %%\n",
                  o.enrolled, o.strangers, o.dir_far1, o.dir_far10, 100 * o.rank1_closed);
      std::printf("open set      at the matcher's threshold: DIR %.3f, strangers accepted %.1f %%, enrolled "
                  "people rejected %.1f %%\n",
                  o.dir_at_threshold, 100 * o.far_at_threshold, 100 * o.missed_at_threshold);
    }
    if (json) {
      nlohmann::json j = {{"rank1", r.rank1},
                                {"rank5", r.rank5},
                                {"rank10", r.rank10},
                                {"rank20", r.rank20},
                                {"map", r.map},
                                {"probes", r.probes},
                                {"gallery", r.gallery},
                                {"ms_per_image", r.ms_per_image},
                                {"same_accepted", r.same_accepted},
                                {"different_rejected", r.different_rejected},
                                {"rank1_per_split", r.rank1_per_split},
                                {"map_per_split", r.map_per_split}};
      if (eval.open_set) {
        const auto per_split = [&](double OpenSetScores::*field) {
          std::vector<double> v;
          for (const auto& split : r.open_set_per_split) v.push_back(split.*field);
          return v;
        };
        const std::pair<const char*, double OpenSetScores::*> fields[] = {
            {"dir_far1", &OpenSetScores::dir_far1},
            {"dir_far10", &OpenSetScores::dir_far10},
            {"dir_at_threshold", &OpenSetScores::dir_at_threshold},
            {"far_at_threshold", &OpenSetScores::far_at_threshold},
            {"missed_at_threshold", &OpenSetScores::missed_at_threshold},
            {"rank1_closed", &OpenSetScores::rank1_closed}};
        for (const auto& [key, field] : fields) {
          j[key] = o.*field;
          j[std::string(key) + "_per_split"] = per_split(field);
        }
        j["enrolled_probes"] = o.enrolled;
        j["stranger_probes"] = o.strangers;
      }
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& eval) {
  auto command = std::make_shared<EvalReidCommand>();
  CLI::App* sub = eval.add_subcommand("reid", "Score person re-identification between two cameras (CMC, mAP)");
  sub->footer(
      "Probes are the first camera's images of the test identities (the second's with --swap-cameras); the "
      "gallery is every other-camera image not used for training (other identities are distractors). Without "
      "--model a learning matcher is trained on each split's training identities only. Matchers: default = LOMO "
      "and GOG variants with XQDA, the variant chosen by cross-validation inside each split's training "
      "identities; default-full = the same on the unsketched features (a model too large to ship); lomo-xqda = the published LOMO + XQDA (Liao et al. 2015); lomo = LOMO with Euclidean "
      "distance, nothing learned; kaze = the thesis's KAZE score.\n"
      "Example: bodyrec eval reid --root ../shared/datasets/viper --id-regex '^images/(\\d{4})' "
      "--cam-regex '^images/\\d{4}(\\d{4})' --train-ids 316 --json");
  add_reid_dataset_options(*sub, command->dataset);
  sub->add_option("--train-ids", command->eval.train_ids,
                  "Identities drawn per split for training (default: half of those in both cameras)")
      ->check(non_negative());
  sub->add_option("--splits", command->eval.splits, "Random splits; figures are their means")->check(positive())
      ->capture_default_str();
  sub->add_option("--seed", command->eval.seed, "Seed of the splits")->capture_default_str();
  sub->add_option("--matcher", command->matcher, "default | default-full | lomo-xqda | lomo | stripes | kaze")->capture_default_str();
  sub->add_option("--model", command->model,
                  "Model from `bodyrec train-reid` for default, default-full or lomo-xqda, used as is in every split (not "
                  "retrained); with --train-ids 0 and no --model, default uses the shipped model");
  sub->add_flag("--swap-cameras", command->eval.swap_cameras,
                "Probes from the second camera, gallery from the first (the other direction)");
  sub->add_option("--resize", command->resize,
                  "Resample every image to WxH before anything else (e.g. 128x256): how sizes other than the "
                  "data set's affect the matcher");
  sub->add_flag("--open-set", command->eval.open_set,
                "Also score open-set identification: per split a random half of the test identities is enrolled "
                "(gallery: their other-camera images and people the probe camera never sees; probes: every "
                "test identity). Prints DIR at FAR 1 % and 10 % (enrolled probes named right and accepted at "
                "the threshold that accepts that share of strangers), the rates at the matcher's own "
                "threshold, and rank-1 among the enrolled");
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (rank1, rank5, rank10, rank20, map, probes, gallery, ms_per_image, "
                "same_accepted, different_rejected: shares of the test's same-person pairs accepted and "
                "different-person pairs rejected at the matcher's threshold; with --open-set also dir_far1, dir_far10, "
                "dir_at_threshold, far_at_threshold, missed_at_threshold, rank1_closed, each with a _per_split "
                "array, enrolled_probes, stranger_probes)");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"eval", 60, add});

}  // namespace
}  // namespace bodyrec::cli
