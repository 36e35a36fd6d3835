// `bodyrec reid REC|VIDEO|--sensor|--camera N [--gallery gallery.db]`: online re-identification of every body
// of an RGB-D recording or sensor, or of every person a plain camera sees, against a persistent gallery
// (thesis Ch6, several people at once): enrolments, recognitions, added views and departures as events,
// written as they are decided, and each body's user per frame. The gallery may be a site's PostgreSQL
// database, and the events go over MQTT with --events (issue 47).
#include <cmath>
#include <cstdio>
#include <functional>
#include <filesystem>
#include <iterator>
#include <map>
#include <set>
#include <memory>

#include "bodyrec/io/json_numbers.h"
#include "bodyrec/io/sinks.h"
#include "bodyrec/store/postgres.h"
#include "command.h"
#include "event_options.h"
#include "gallery_spools.h"
#include "reid_output.h"
#include "stop_signal.h"

namespace bodyrec::cli {
namespace {

// What --prune-unseen-for erased leaves the other spools the gallery lists on this machine too (this run's
// own is withdrawn by its publisher); a line on stderr for each spool that lost events or could not be
// scrubbed, so that stdout stays the run's.
void scrub_pruned(Gallery& gallery, const std::function<bool(int64_t user)>& exists) {
  const SpoolScrubs pruned = scrub_spools(gallery, {}, [&](int64_t user) { return !exists(user); }, nullptr);
  for (const nlohmann::json& spool : pruned.spools) {
    const std::string path = spool["path"];
    if (spool["status"] == "error")
      std::fprintf(stderr, "bodyrec: event spool %s not scrubbed: %s\n", path.c_str(),
                   spool["error"].get<std::string>().c_str());
    else if (spool["removed"].get<size_t>() > 0)
      std::fprintf(stderr, "bodyrec: withdrew %zu events of pruned users from the event spool %s\n",
                   spool["removed"].get<size_t>(), path.c_str());
  }
}

struct ReidCommand {
  std::string input, jsonl;
  ReidCliOptions options;
  EventCliOptions event_options;
  bool json = false, quiet = false;

  // A gallery file that this run creates is removed again when the run fails before its first frame, so a
  // refused input or an unwritable output leaves no empty gallery behind.
  void run() const {
    const std::string& path = options.gallery.path;
    std::error_code ec;
    const bool new_file = !sql::is_postgres_uri(path) && !std::filesystem::exists(path, ec);
    bool processed = false;
    try {
      run_frames(processed);
    } catch (...) {
      if (new_file && !processed)
        for (const char* suffix : {"", "-wal", "-shm", "-journal"}) std::filesystem::remove(path + suffix, ec);
      throw;
    }
  }

  void run_frames(bool& processed) const {
    check_input_given(input, options.orient.live, options.colour.camera);
    StopOnSignal stop;  // SIGINT/SIGTERM: the run ends after its frame, outputs whole, gallery committed, exit 0
    ReidInput in = open_reid_input(input, options);  // before any file is created
    RunEvents events = open_events(event_options, "reid");
    ReidCliOptions o = options;
    o.sensor = events.sensor;
    std::unique_ptr<JsonlWriter> lines;
    if (!jsonl.empty()) lines = std::make_unique<JsonlWriter>(jsonl);
    const bool text = !quiet && jsonl != "-";
    auto gallery = open_reid_gallery(o, o.gallery.path);
    list_run_spool(*gallery, events);  // so that gallery forget finds this run's undelivered events
    const std::string source = options.colour.camera >= 0 ? "camera " + std::to_string(options.colour.camera)
                               : in.source                 ? in.source->name()
                                                           : input;
    GalleryReidStore store(*gallery, *in.matcher, {source, gallery_clock_start(in, options)});
    if (!options.no_images && !gallery->options().store_images)
      std::fprintf(stderr, "bodyrec: %s holds features only (kept with --no-images): this run stores no images either\n",
                   gallery->path().c_str());
    // Users erased from the gallery are never published: not from what an earlier run left in the spool,
    // nor from this run's undelivered events once another process erases them (checked after each frame).
    const auto exists = [&store](int64_t user) { return store.has_user(user); };
    events.withdraw_erased(exists);
    if (!options.prune_unseen_for.empty()) scrub_pruned(*gallery, exists);
    std::set<int64_t> published;  // users with events given to the publisher
    std::map<std::string, int> counts;
    int bodies = 0, last_frame = -1;
    double last_time = 0, ms = 0;
    const ReidRunStats stats = run_reid(in, o, store, [&](const ReidFrame& f) {
      processed = true;
      if (f.frame.index >= 0) {
        last_frame = f.frame.index;
        last_time = f.frame.time_s;
        bodies += static_cast<int>(f.step.identities.size());
        ms += f.ms_orient + f.ms_scan + f.ms_reid;
      }
      for (const ReidEvent& e : f.step.events) {
        ++counts[reid_event_name(e.kind)];
        nlohmann::json payload = reid_event_json(e);
        payload["frame"] = f.frame.index >= 0 ? f.frame.index : last_frame + 1;
        payload["time"] = f.frame.index >= 0 ? f.frame.time_s : last_time;
        if (f.frame.index < 0) payload["end"] = true;
        payload["source"] = in.path;
        events.publish(std::move(payload));
        if (events.publisher) published.insert(e.user);
        if (!text) continue;
        std::printf("frame %d track %llu %s user %lld", f.frame.index >= 0 ? f.frame.index : last_frame,
                    static_cast<unsigned long long>(e.track), reid_event_name(e.kind), static_cast<long long>(e.user));
        if (e.view) std::printf(" view %s", view_name(*e.view));
        if (e.score) std::printf(" score %.3f", *e.score);
        std::printf("\n");
      }
      if (text && !f.step.events.empty()) std::fflush(stdout);  // as they happen, also into a pipe
      if (lines) lines->write(reid_frame_json(f, last_frame + 1, last_time));
      const size_t before = published.size();
      for (auto u = published.begin(); u != published.end();) u = exists(*u) ? std::next(u) : published.erase(u);
      if (published.size() < before) events.withdraw_erased(exists);
    });
    // An erasure while the last frames were decided: withdrawn before the publisher's final wait.
    store.refresh();
    events.withdraw_erased(exists);
    const nlohmann::json delivery = events.finish();
    const int frames = stats.frames;
    const double p50 = percentile(stats.latency_ms, 50), p95 = percentile(stats.latency_ms, 95);
    const int users = gallery->user_count();
    const double per_frame = frames ? ms / frames : 0.0, per_body = bodies ? ms / bodies : 0.0;
    if (text)
      std::printf("frames %d, body-frames %d, enrolled %d, recognised %d, views added %d, left %d; gallery %s: %d %s; "
                  "%.2f ms per frame, %.2f ms per body\n",
                  frames, bodies, counts["enrolled"], counts["recognised"], counts["view_added"], counts["left"],
                  gallery->path().c_str(), users, users == 1 ? "user" : "users", per_frame, per_body);
    if (text && (stats.dropped > 0 || options.orient.live.live() || options.colour.camera >= 0))
      std::printf("dropped %ld frames; event latency p50 %.1f ms, p95 %.1f ms%s\n", stats.dropped, p50, p95,
                  stats.stopped ? "; stopped by a signal" : "");
    if (json)
      std::printf("%s\n", json_text(nlohmann::json({{"frames", frames},
                                          {"body_frames", bodies},
                                          {"enrolled", counts["enrolled"]},
                                          {"recognised", counts["recognised"]},
                                          {"view_added", counts["view_added"]},
                                          {"left", counts["left"]},
                                          {"users", users},
                                          {"ms_per_frame", per_frame},
                                          {"ms_per_body", per_body},
                                          {"dropped", stats.dropped},
                                          {"latency_ms_p50", std::round(p50 * 100) / 100},
                                          {"latency_ms_p95", std::round(p95 * 100) / 100},
                                          {"stopped", stats.stopped},
                                          {"colour_only", in.colour != nullptr},
                                          {"matcher", options.matcher},
                                          {"match_views", to_string(match_views(options))},
                                          {"sensor", events.sensor},
                                          {"events", delivery}}))
                              .c_str());
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<ReidCommand>();
  CLI::App* sub = app.add_subcommand(
      "reid",
      "Re-identify people online from an RGB-D recording or sensor, or a plain camera (video, images, --camera): "
      "enrol new users, recognise known ones (gallery)");
  sub->add_option("INPUT", command->input,
                  "A recording (bodyrec record/import/synth: colour, depth, and bodies or body index when it has "
                  "them), or a plain camera's video, image folder or glob (or --sensor, --camera N)");
  add_reid_options(*sub, command->options, true, true);
  add_live_options(*sub, command->options.orient.live, true, true);
  add_sensor_option(*sub, command->event_options);
  add_event_options(*sub, command->event_options);
  sub->add_option("--jsonl", command->jsonl,
                  "Per frame, written and flushed as it is decided: each body's track, user (null while undecided), "
                  "view, box; the events; ms per stage; live runs add arrival and wall (Unix seconds) and dropped. "
                  "'-' = stdout");
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (frames, body_frames, enrolled, recognised, view_added, left, users, "
                "ms_per_frame, ms_per_body, dropped, latency_ms_p50, latency_ms_p95: from a frame's arrival to its "
                "events' flush, stopped, colour_only, sensor, events: {delivered, pending, dropped, recovered, "
                "spool, topic} with --events)");
  sub->add_flag("-q,--quiet", command->quiet, "No per-event lines");
  sub->footer(
      "SIGINT or SIGTERM ends a run cleanly (outputs whole, gallery committed, exit 0).\n"
      "Example: bodyrec synth --scenario reenter --people 4 --frames 300 --out rec -q && "
      "bodyrec reid rec --gallery gallery.db --jsonl reid.jsonl && bodyrec report reid.jsonl --gallery "
      "gallery.db --out report.html\n"
      "         bodyrec reid /usr/share/doc/opencv-doc/examples/data/vtest.avi --gallery g.db --jsonl -\n"
      "         bodyrec reid rec --colour-only --gallery g.db   (the recording's colour alone)\n"
      "         bodyrec reid --sensor --gallery g.db   (a live OpenNI2 sensor, until Ctrl-C)\n"
      "Several sensors: bodyrec reid rec --gallery postgresql://bodyrec_sensor@db.site/bodyrec_site "
      "--sensor-id door --events mqtt://broker.site/site --events-credentials door.cred (docs/guides/sites.md)");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 63, add});

}  // namespace
}  // namespace bodyrec::cli
