// `bodyrec reid REC [--gallery gallery.db]`: online re-identification of every body of an RGB-D
// recording against a persistent gallery (thesis Ch6, several people at once): enrolments,
// recognitions, added views and departures as events, and each body's user per frame.
#include <cstdio>
#include <map>
#include <memory>

#include "bodyrec/io/sinks.h"
#include "command.h"
#include "reid_output.h"

namespace bodyrec::cli {
namespace {

struct ReidCommand {
  std::string input, jsonl;
  ReidCliOptions options;
  bool json = false, quiet = false;

  void run() const {
    ReidInput in = open_reid_input(input, options);  // before any file is created
    std::unique_ptr<JsonlWriter> lines;
    if (!jsonl.empty()) lines = std::make_unique<JsonlWriter>(jsonl);
    const bool text = !quiet && jsonl != "-";
    auto gallery = open_reid_gallery(options, options.gallery.path);
    GalleryReidStore store(*gallery, *in.matcher, {input, std::nullopt});
    std::map<std::string, int> counts;
    int bodies = 0, last_frame = -1;
    double last_time = 0, ms = 0;
    const int frames = run_reid(in, options, store, [&](const ReidFrame& f) {
      if (f.frame.index >= 0) {
        last_frame = f.frame.index;
        last_time = f.frame.time_s;
        bodies += static_cast<int>(f.step.identities.size());
        ms += f.ms_orient + f.ms_scan + f.ms_reid;
      }
      for (const ReidEvent& e : f.step.events) {
        ++counts[reid_event_name(e.kind)];
        if (!text) continue;
        std::printf("frame %d track %llu %s user %lld", f.frame.index >= 0 ? f.frame.index : last_frame,
                    static_cast<unsigned long long>(e.track), reid_event_name(e.kind), static_cast<long long>(e.user));
        if (e.view) std::printf(" view %s", view_name(*e.view));
        if (e.score) std::printf(" score %.3f", *e.score);
        std::printf("\n");
      }
      if (lines) lines->write(reid_frame_json(f, last_frame + 1, last_time));
    });
    const int users = gallery->user_count();
    const double per_frame = frames ? ms / frames : 0.0, per_body = bodies ? ms / bodies : 0.0;
    if (text)
      std::printf("frames %d, body-frames %d, enrolled %d, recognised %d, views added %d, left %d; gallery %s: %d %s; "
                  "%.2f ms per frame, %.2f ms per body\n",
                  frames, bodies, counts["enrolled"], counts["recognised"], counts["view_added"], counts["left"],
                  gallery->path().c_str(), users, users == 1 ? "user" : "users", per_frame, per_body);
    if (json)
      std::printf("%s\n", nlohmann::json({{"frames", frames},
                                          {"body_frames", bodies},
                                          {"enrolled", counts["enrolled"]},
                                          {"recognised", counts["recognised"]},
                                          {"view_added", counts["view_added"]},
                                          {"left", counts["left"]},
                                          {"users", users},
                                          {"ms_per_frame", per_frame},
                                          {"ms_per_body", per_body},
                                          {"matcher", options.matcher},
                                          {"match_views", to_string(match_views(options))}})
                              .dump()
                              .c_str());
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<ReidCommand>();
  CLI::App* sub = app.add_subcommand(
      "reid", "Re-identify people in an RGB-D recording online: enrol new users, recognise known ones (gallery)");
  sub->add_option("REC", command->input, "Recording (bodyrec record/import/synth): colour, depth, and bodies or body "
                                         "index when it has them")
      ->required();
  add_reid_options(*sub, command->options);
  sub->add_option("--jsonl", command->jsonl,
                  "Per frame: each body's track, user (null while undecided), view, box; the events; ms per stage. "
                  "'-' = stdout");
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (frames, body_frames, enrolled, recognised, view_added, left, users, "
                "ms_per_frame, ms_per_body)");
  sub->add_flag("-q,--quiet", command->quiet, "No per-event lines");
  sub->footer("Example: bodyrec synth --scenario reenter --people 4 --frames 300 --out rec -q && "
              "bodyrec reid rec --gallery gallery.db --jsonl reid.jsonl && bodyrec report reid.jsonl --gallery "
              "gallery.db --out report.html");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 63, add});

}  // namespace
}  // namespace bodyrec::cli
