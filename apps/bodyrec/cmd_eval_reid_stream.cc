// `bodyrec eval reid-stream REC`: runs online re-identification over a recording with truth (bodyrec
// synth) on a fresh store in memory (or --gallery) and scores it: per-frame identity accuracy, splits, merges
// (eval/reid_stream_metrics.h), ms per frame.
#include <cstdio>
#include <memory>

#include "bodyrec/core/error.h"
#include "bodyrec/eval/reid_stream_metrics.h"
#include "bodyrec/io/sinks.h"
#include "bodyrec/reid/memory_reid_store.h"
#include "command.h"
#include "reid_output.h"

namespace bodyrec::cli {
namespace {

struct EvalReidStreamCommand {
  std::string input, jsonl, gallery;
  ReidCliOptions options;
  bool json = false;

  void run() const {
    ReidInput in = open_reid_input(input, options);  // before any file is created
    std::unique_ptr<JsonlWriter> lines;
    if (!jsonl.empty()) lines = std::make_unique<JsonlWriter>(jsonl);
    // A fresh store in memory unless a gallery is named.
    std::unique_ptr<Gallery> g;
    std::unique_ptr<ReidStore> store;
    if (gallery.empty()) {
      store = std::make_unique<MemoryReidStore>();
    } else {
      g = open_reid_gallery(options, gallery);
      store = std::make_unique<GalleryReidStore>(*g, *in.matcher, GalleryReidStoreOptions{input, std::nullopt});
    }
    ReidStreamCounter counter;
    bool any_truth = false;
    int last_frame = -1;
    double ms = 0, last_time = 0;
    const int frames = run_reid(in, options, *store, [&](const ReidFrame& f) {
      if (f.frame.index >= 0) {
        last_frame = f.frame.index;
        last_time = f.frame.time_s;
        ms += f.ms_orient + f.ms_scan + f.ms_reid;
      }
      if (lines) {
        // The run's line, plus each body's true person (identity; null when it matches nobody).
        nlohmann::json j = reid_frame_json(f, last_frame + 1, last_time);
        for (size_t i = 0; i < f.bodies.size(); ++i) {
          const int t = f.bodies[i].truth;
          j["bodies"][i]["person"] = f.frame.truth && t >= 0
                                         ? nlohmann::json(f.frame.truth->people[static_cast<size_t>(t)].identity)
                                         : nlohmann::json();
        }
        lines->write(j);
      }
      if (f.frame.truth) {
        any_truth = true;
        for (size_t i = 0; i < f.bodies.size(); ++i) {
          const OrientedBody& b = f.bodies[i];
          if (b.truth >= 0)
            counter.add(f.frame.truth->people[static_cast<size_t>(b.truth)].identity, b.key, f.step.identities[i].user);
        }
      }
      for (const ReidEvent& e : f.step.events)
        if (e.kind == ReidEventKind::kEnrolled || e.kind == ReidEventKind::kRecognised) counter.assign(e.track, e.user);
    });
    if (!any_truth) throw InputError(input + ": the recording has no truth stream (make one with bodyrec synth)");
    const ReidStreamScore s = counter.score();
    const double per_frame = frames ? ms / frames : 0.0;
    std::printf("frames        %d (%d body-frames with a true person)\n", frames, s.frames);
    std::printf("accuracy      %.4f (right user / body-frames; %d still undecided count wrong)\n", s.accuracy,
                s.undecided);
    std::printf("people        %d true identities, %d users, %d tracks\n", s.identities, s.users, s.tracks);
    std::printf("splits        %d (one person enrolled as more than one user)\n", s.splits);
    std::printf("merges        %d (two people given one user)\n", s.merges);
    std::printf("ms per frame  %.2f (%s matcher)\n", per_frame, options.matcher.c_str());
    if (json)
      std::printf("%s\n", nlohmann::json({{"accuracy", s.accuracy},
                                          {"splits", s.splits},
                                          {"merges", s.merges},
                                          {"frames", frames},
                                          {"body_frames", s.frames},
                                          {"undecided", s.undecided},
                                          {"users", s.users},
                                          {"identities", s.identities},
                                          {"ms_per_frame", per_frame},
                                          {"matcher", options.matcher},
                                          {"match_views", to_string(match_views(options))}})
                              .dump()
                              .c_str());
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<EvalReidStreamCommand>();
  CLI::App* sub = app.add_subcommand(
      "reid-stream", "Score online re-identification on a recording with truth: per-frame accuracy, splits, merges");
  sub->add_option("REC", command->input, "Recording with a truth stream (bodyrec synth)")->required();
  sub->add_option("--gallery", command->gallery,
                  "Start from (and write to) this gallery instead of a fresh one in memory");
  add_reid_options(*sub, command->options, false);
  sub->add_option("--jsonl", command->jsonl, "The run's per-frame output, as `bodyrec reid --jsonl` writes it, each body with its true \"person\" (identity, null when none)");
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (accuracy, splits, merges, frames, body_frames, undecided, users, "
                "identities, ms_per_frame)");
  sub->footer("Example: bodyrec synth --scenario reenter --people 5 --frames 300 --seed 2 --out rec -q && "
              "bodyrec eval reid-stream rec --json");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"eval", 64, add});

}  // namespace
}  // namespace bodyrec::cli
