// `bodyrec eval orient REC`: view accuracy against the truth of a synthetic recording. The true view is
// the nearest 45-degree sector of the truth yaw (reid/orientation.h); a body without a view counts as
// wrong. Bodies whose visible fraction is below --min-visible are left out (and counted).
#include <array>
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/sinks.h"
#include "command.h"
#include "orient_job.h"

namespace bodyrec::cli {
namespace {

struct EvalOrientCommand {
  std::string input, jsonl;
  OrientCliOptions options;
  double min_visible = 0.5;
  bool json = false;

  void run() const {
    if (is_skeleton_file(input)) throw InputError(input + ": eval orient needs a recording with truth (bodyrec synth)");
    std::unique_ptr<JsonlWriter> lines;
    if (!jsonl.empty()) lines = std::make_unique<JsonlWriter>(jsonl);
    int scored = 0, correct = 0, adjacent = 0, excluded = 0, no_view = 0, unmatched = 0, with_yaw = 0, bodies = 0;
    double yaw_err = 0, ms = 0;
    bool any_truth = false;
    std::array<std::array<int, kViewCount>, kViewCount> confusion{};
    const int frames = run_orientation(input, options, [&](const OrientFrame& f) {
      ms += f.result.ms;
      bodies += static_cast<int>(f.result.bodies.size());
      if (!f.frame.truth) return;
      any_truth = true;
      for (const OrientedBody& b : f.result.bodies) {
        if (b.truth < 0) {
          ++unmatched;
          continue;
        }
        const PersonTruth& t = f.frame.truth->people[static_cast<size_t>(b.truth)];
        if (t.visible_fraction < min_visible) {
          ++excluded;
          continue;
        }
        ++scored;
        const View truth_view = view_of_yaw(t.yaw_deg);
        const ViewEstimate& v = b.view;
        if (!v.view) ++no_view;
        else {
          confusion[static_cast<size_t>(truth_view)][static_cast<size_t>(*v.view)]++;
          correct += *v.view == truth_view;
          adjacent += angle_diff_deg(view_yaw_deg(*v.view), view_yaw_deg(truth_view)) <= 45.5;
        }
        if (v.has_yaw) {
          ++with_yaw;
          yaw_err += angle_diff_deg(v.yaw_deg, t.yaw_deg);
        }
        if (lines)
          lines->write({{"frame", f.frame.index},
                        {"identity", t.identity},
                        {"truth_yaw_deg", t.yaw_deg},
                        {"truth_view", view_name(truth_view)},
                        {"yaw_deg", v.has_yaw ? nlohmann::json(v.yaw_deg) : nlohmann::json()},
                        {"view", v.view ? nlohmann::json(view_name(*v.view)) : nlohmann::json()},
                        {"confidence", v.confidence},
                        {"source", v.source},
                        {"face", b.face.looked ? nlohmann::json(b.face.face) : nlohmann::json()},
                        {"visible_fraction", t.visible_fraction}});
      }
    });
    if (!any_truth) throw InputError(input + ": the recording has no truth stream (make one with bodyrec synth)");
    const double accuracy = scored ? static_cast<double>(correct) / scored : 0.0;
    const double within_one = scored ? static_cast<double>(adjacent) / scored : 0.0;
    const double mae = with_yaw ? yaw_err / with_yaw : 0.0;
    const double per_body = bodies ? ms / bodies : 0.0;
    std::printf("frames        %d\n", frames);
    std::printf("scored        %d body-frames (excluded %d below visible fraction %.2f, %d without a true person)\n",
                scored, excluded, min_visible, unmatched);
    std::printf("accuracy      %.4f (view = nearest 45-degree sector of the truth yaw; no view %d counts wrong)\n",
                accuracy, no_view);
    std::printf("within one    %.4f (the true view or a neighbour)\n", within_one);
    std::printf("yaw error     %.2f degrees mean absolute (%d body-frames with a yaw)\n", mae, with_yaw);
    std::printf("ms per body   %.3f (%s views%s)\n", per_body, view_method_name(options.pipeline.orientation.method),
                options.pipeline.bodies.depth_only ? ", depth only" : "");
    std::printf("confusion     rows truth, columns estimate:");
    for (View c : kAllViews) std::printf(" %3s", view_name(c));
    std::printf("\n");
    for (View r : kAllViews) {
      std::printf("              %-2s", view_name(r));
      for (View c : kAllViews) std::printf(" %3d", confusion[static_cast<size_t>(r)][static_cast<size_t>(c)]);
      std::printf("\n");
    }
    if (json)
      std::printf("%s\n", nlohmann::json({{"accuracy", accuracy},
                                          {"within_one", within_one},
                                          {"scored", scored},
                                          {"excluded", excluded},
                                          {"no_view", no_view},
                                          {"yaw_mae_deg", mae},
                                          {"frames", frames},
                                          {"ms_per_body", per_body}})
                              .dump()
                              .c_str());
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<EvalOrientCommand>();
  CLI::App* sub = app.add_subcommand("orient", "Score body orientation views against a synthetic recording's truth");
  sub->add_option("REC", command->input, "Recording with a truth stream (bodyrec synth)")->required();
  add_orient_options(*sub, command->options);
  sub->add_flag("--face-oracle", command->options.pipeline.face_oracle,
                "Face flag from the truth yaw (|yaw| < 90) instead of the face detector: measures the view rule alone");
  sub->add_option("--min-visible", command->min_visible, "Bodies with a smaller visible fraction are not scored")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  sub->add_option("--jsonl", command->jsonl, "Per scored body: truth and estimated yaw and view, as JSON lines");
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (accuracy, within_one, scored, excluded, no_view, yaw_mae_deg, frames, "
                "ms_per_body)");
  sub->footer("Example: bodyrec synth --people 4 --seed 3 --frames 120 --scenario cross --out rec -q && "
              "bodyrec eval orient rec --json");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"eval", 62, add});

}  // namespace
}  // namespace bodyrec::cli
