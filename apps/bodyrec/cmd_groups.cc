// `bodyrec groups`: the group-leader tracker (thesis Ch4) on a video or camera: people, tracks, motion,
// groups and roles (leader / member / non-member), leader tracking with loss and re-acquisition, and the
// leader's direction. With --events, leader found/lost and group formed/dissolved go over MQTT (issue 47).
#include <cstdio>
#include <iostream>

#include <nlohmann/json.hpp>

#include "bodyrec/groups/group_events.h"
#include "bodyrec/io/json_numbers.h"
#include "command.h"
#include "common_options.h"
#include "event_options.h"
#include "groups_job.h"
#include "stop_signal.h"

namespace bodyrec::cli {
namespace {

struct GroupsCommand {
  SourceOptions source;
  OutputOptions outputs;
  DetectorOptions detector;
  GroupsJobOptions groups;
  EventCliOptions event_options;
  bool json = false;

  void run() const {
    groups.tracking.tracker.check();
    groups.resolved();
    // groups keeps no gallery: its sensor id goes only into MQTT events.
    if (!event_options.sensor.empty() && event_options.uri.empty())
      throw UsageError("--sensor-id names the sensor in MQTT events: it needs --events");
    StopOnSignal stop;  // SIGINT/SIGTERM end a live run after its frame: outputs whole, summary written, exit 0
    auto frames = open_source(source);
    auto people = make_detector(detector, *frames);
    RunEvents events = open_events(event_options, "groups");
    GroupFrame previous;
    int last_frame = -1;
    double last_time = 0;
    const auto publish = [&](const GroupFrame& now, int frame, double time, bool end) {
      for (const GroupEvent& e : group_events(previous, now)) {
        nlohmann::json payload = {{"kind", group_event_name(e.kind)}, {"group", e.group}, {"members", e.members},
                                  {"frame", frame},                    {"time", time},
                                  {"source", source.path.empty() ? "camera " + std::to_string(source.camera) : source.path}};
        if (e.leader) payload["leader"] = *e.leader;
        if (e.previous) payload["previous"] = *e.previous;
        if (!e.reason.empty()) payload["reason"] = e.reason;
        if (end) payload["end"] = true;
        events.publish(std::move(payload));
      }
      previous = now;
    };
    std::map<std::string, int> role_boxes;
    int lost_events = 0, reacquired = 0, handovers = 0, max_groups = 0;
    const auto stats = run_groups(*frames, *people, groups, outputs, !json || !outputs.jsonl.empty(),
                                  [&](const Frame& frame, const GroupFrame& g) {
                                    last_frame = frame.index;
                                    last_time = groups.fps > 0 ? frame.index / groups.fps : frame.time_s;
                                    if (events.publisher) publish(g, last_frame, last_time, false);
                                    for (const auto& p : g.people) role_boxes[to_string(p.role)]++;
                                    for (const auto& l : g.leaders) {
                                      lost_events += !l.status.lost_reason.empty();
                                      reacquired += l.status.reacquired;
                                      handovers += l.status.handed_over_from.has_value();
                                    }
                                    max_groups = std::max(max_groups, static_cast<int>(g.leaders.size()));
                                  });
    if (events.publisher) publish(GroupFrame{}, last_frame, last_time, true);  // the run ends every group
    const nlohmann::json delivery = events.finish();
    const double n = std::max(1, stats.frames);
    if (stats.stopped) std::cerr << "bodyrec groups: stopped by a signal after " << stats.frames << " frames\n";
    if (!outputs.quiet)
      std::cerr << "bodyrec groups: " << stats.frames << " frames, " << stats.total_ms() / n
                << " ms per frame (detection+tracking " << stats.tracking_ms / n << ", motion "
                << stats.stages.motion / n << ", groups " << stats.stages.groups / n << ", roles "
                << stats.stages.roles / n << ", leader " << stats.stages.leader / n << ", flow "
                << stats.stages.flow / n << ")\n";
    if (json) {
      const nlohmann::json summary = {
          {"frames", stats.frames},
          {"stopped", stats.stopped},
          {"ms_per_frame", stats.total_ms() / n},
          {"ms", {{"tracking", stats.tracking_ms / n}, {"motion", stats.stages.motion / n},
                  {"groups", stats.stages.groups / n}, {"roles", stats.stages.roles / n},
                  {"leader", stats.stages.leader / n}, {"flow", stats.stages.flow / n}}},
          {"role_boxes", role_boxes},
          {"max_groups", max_groups},
          {"leader_lost", lost_events},
          {"leader_reacquired", reacquired},
          {"leader_handovers", handovers},
          {"sensor", events.publisher ? nlohmann::json(events.sensor) : nlohmann::json(nullptr)},
          {"events", delivery}};
      std::printf("%s\n", json_text(summary).c_str());
    }
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<GroupsCommand>();
  CLI::App* sub = app.add_subcommand(
      "groups", "Find groups, their leaders, members and passers-by; track each leader and its direction");
  sub->footer(
      "Writes one JSON object per frame: {\"frame\",\"time\",\"motion\":{\"valid\",\"deviation\",\"box\"},"
      "\"people\":[{\"id\",\"box\",\"state\",\"role\":\"leader\"|\"member\"|\"non-member\"|\"potential-member\"|"
      "\"unknown\",\"group\",\"motion\",\"ground\"}],\"leaders\":[{\"group\",\"id\",\"state\":\"tracking\"|\"lost\","
      "\"psr\",\"reacquired\",\"box\",\"lost_reason\",\"handed_over_from\",\"direction\":{\"degrees\","
      "\"magnitude\",\"samples\"}}],\"ms\":{...}}\n"
      "Direction: degrees counter-clockwise from image right (90 = up), magnitude in pixels per frame.\n"
      "Example: bodyrec groups /usr/share/doc/opencv-doc/examples/data/vtest.avi --fps 7 "
      "--calibration ../shared/datasets/pets09_s2l1/View_001.xml --jsonl out/groups.jsonl "
      "--annotate out/groups.avi");
  add_source_options(*sub, command->source);
  add_output_options(*sub, command->outputs);
  add_detector_options(*sub, command->detector, DetectorUse::kTrack);
  add_groups_options(*sub, command->groups);
  add_sensor_option(*sub, command->event_options);
  add_event_options(*sub, command->event_options);
  sub->add_flag("--json", command->json,
                "End stdout with one JSON summary (frames, ms_per_frame and per stage, role counts, leader "
                "losses); per-frame rows then go only to --jsonl");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 25, add});

}  // namespace
}  // namespace bodyrec::cli
