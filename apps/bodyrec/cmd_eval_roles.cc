// `bodyrec eval roles`: the thesis's role accuracy of the group-leader pipeline against hand-labelled
// roles (CSV frame,x,y,w,h,role) on sampled frames.
#include <cstdio>
#include <map>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/eval/role_metrics.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/io/roles_csv.h"
#include "command.h"
#include "common_options.h"
#include "groups_job.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

struct EvalRolesCommand {
  SourceOptions source;
  OutputOptions outputs;
  DetectorOptions detector;
  GroupsJobOptions groups;
  std::string gt;
  double iou = 0.5;
  bool json = false;

  void run() const {
    if (source.path.empty()) throw UsageError("eval roles needs --source VIDEO");
    groups.tracking.tracker.check();
    groups.resolved();
    std::map<int, std::vector<RoleBox>> labelled;
    for (const auto& l : read_roles_csv(gt)) labelled[l.frame].push_back({l.box, l.role});
    if (labelled.empty()) throw InputError(gt + ": no labelled boxes");
    auto frames = open_source(source);
    auto people = make_detector(detector, *frames);
    RoleEvaluator evaluator(iou);
    const auto stats = run_groups(*frames, *people, groups, outputs, !outputs.jsonl.empty(),
                                  [&](const Frame& frame, const GroupFrame& g) {
                                    const auto it = labelled.find(frame.index);
                                    if (it == labelled.end()) return;
                                    std::vector<RoleBox> system;
                                    for (const auto& p : g.people) system.push_back({p.box, p.role});
                                    evaluator.add_frame(it->second, system);
                                  });
    const RoleScores s = evaluator.scores();
    if (s.boxes == 0)
      throw InputError(gt + ": no labelled box in the " + std::to_string(stats.frames) +
                       " frames processed (its frames are " + std::to_string(labelled.begin()->first) + "-" +
                       std::to_string(labelled.rbegin()->first) + ")");
    const double ms = stats.frames ? stats.total_ms() / stats.frames : 0.0;
    std::printf("roles         %s\n", to_string(groups.pipeline.roles));
    std::printf("frames        %d labelled frames scored (of %zu in %s; %d processed)\n", s.frames, labelled.size(),
                gt.c_str(), stats.frames);
    std::printf("boxes         %d labelled, %d matched to a tracked box at IoU >= %.2f\n", s.boxes, s.matched, iou);
    std::printf("accuracy      %.4f  (leader correct %d + member/non-member correct %d) / boxes\n", s.accuracy,
                s.leader_correct, s.member_correct);
    std::printf("matched only  %.4f\n", s.accuracy_matched);
    for (const auto& [truth, row] : s.confusion) {
      std::printf("  labelled %-10s ->", truth.c_str());
      for (const auto& [said, n] : row) std::printf(" %s %d", said.c_str(), n);
      std::printf("\n");
    }
    std::printf("ms per frame  %.2f (whole pipeline)\n", ms);
    if (json) {
      const nlohmann::json j = {{"accuracy", s.accuracy},       {"accuracy_matched", s.accuracy_matched},
                                {"boxes", s.boxes},             {"matched", s.matched},
                                {"leader_correct", s.leader_correct}, {"member_correct", s.member_correct},
                                {"frames", s.frames},           {"confusion", s.confusion},
                                {"ms_per_frame", ms}};
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& eval) {
  auto command = std::make_shared<EvalRolesCommand>();
  CLI::App* sub = eval.add_subcommand("roles", "Score leader / member / non-member roles against hand labels");
  sub->footer("Accuracy as in the thesis: (leader correct + member correct) / labelled boxes, where member "
              "correct includes non-members called non-members; unmatched labelled boxes count as wrong.\n"
              "Example: bodyrec eval roles --source /usr/share/doc/opencv-doc/examples/data/vtest.avi "
              "--gt data/roles/vtest_roles.csv --fps 7 --calibration "
              "../shared/datasets/pets09_s2l1/View_001.xml --json");
  add_source_options(*sub, command->source, true);
  sub->add_option("--gt", command->gt, "Hand-labelled roles: CSV frame,x,y,w,h,role (leader|member|non-member)")
      ->required();
  sub->add_option("--iou", command->iou, "IoU a tracked box needs to match a labelled box")
      ->check(in_range(0.05, 1.0))->capture_default_str();
  sub->add_flag("--json", command->json, "End stdout with one JSON object (accuracy, boxes, matched, ...)");
  add_output_options(*sub, command->outputs);
  add_detector_options(*sub, command->detector, DetectorUse::kTrack);
  add_groups_options(*sub, command->groups);
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"eval", 30, add});

}  // namespace
}  // namespace bodyrec::cli
