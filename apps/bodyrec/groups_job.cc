#include "groups_job.h"

#include <cmath>
#include <map>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/annotate.h"
#include "bodyrec/io/progress.h"
#include "bodyrec/io/sinks.h"
#include "enum_option.h"
#include "frame_errors.h"
#include "option_checks.h"
#include "run_sinks.h"
#include "stop_signal.h"

namespace bodyrec::cli {
namespace {

nlohmann::json box_json(const Box& b) { return {b.x, b.y, b.width, b.height}; }
double round2(double v) { return std::round(v * 100) / 100; }

nlohmann::json frame_json(const Frame& frame, double t, const GroupFrame& g) {
  nlohmann::json row = {{"frame", frame.index}, {"time", round2(t * 1000) / 1000}};
  nlohmann::json motion = {{"valid", g.motion_valid}, {"deviation", round2(g.motion_deviation)}};
  if (g.motion_box) motion["box"] = box_json(round_box_for_output(*g.motion_box));
  row["motion"] = motion;
  row["people"] = nlohmann::json::array();
  for (const auto& p : g.people) {
    nlohmann::json person = {{"id", p.id},           {"box", box_json(p.box)},
                             {"state", to_string(p.state)}, {"role", to_string(p.role)},
                             {"group", p.group},     {"motion", round2(p.motion_energy * 1000) / 1000}};
    if (p.ground) person["ground"] = {round2(p.ground->x), round2(p.ground->y)};
    row["people"].push_back(person);
  }
  row["leaders"] = nlohmann::json::array();
  for (const auto& l : g.leaders) {
    nlohmann::json leader = {{"group", l.group},
                             {"id", l.status.track_id},
                             {"state", to_string(l.status.state)},
                             {"psr", round2(l.status.psr)},
                             {"reacquired", l.status.reacquired}};
    if (l.status.state == LeaderState::kTracking) leader["box"] = box_json(round_box_for_output(l.status.box));
    if (l.status.handed_over_from) leader["handed_over_from"] = *l.status.handed_over_from;
    if (!l.status.lost_reason.empty()) leader["lost_reason"] = l.status.lost_reason;
    if (l.direction)
      leader["direction"] = {{"degrees", round2(l.direction->degrees)},
                             {"magnitude", round2(l.direction->magnitude)},
                             {"samples", l.direction->samples}};
    row["leaders"].push_back(leader);
  }
  row["ms"] = {{"motion", round2(g.ms.motion)}, {"groups", round2(g.ms.groups)}, {"roles", round2(g.ms.roles)},
               {"leader", round2(g.ms.leader)}, {"flow", round2(g.ms.flow)}};
  return row;
}

void draw(cv::Mat& canvas, const Frame& frame, const GroupFrame& g) {
  if (g.motion_box) draw_labelled_box(canvas, *g.motion_box, colors::kYellow, "", 1);
  for (const auto& p : g.people) {
    std::string label = std::to_string(p.id);
    if (p.group >= 0) label += " g" + std::to_string(p.group);
    draw_labelled_box(canvas, p.box, role_color(p.role), label, p.state == TrackState::kLost ? 1 : 2);
  }
  int lost = 0;
  for (const auto& l : g.leaders) {
    if (l.status.state == LeaderState::kLost) ++lost;
    if (l.status.state != LeaderState::kTracking) continue;
    cv::rectangle(canvas, cv::Rect(l.status.box), colors::kBlue, 3, cv::LINE_AA);
    if (l.direction && l.direction->magnitude > 0.05) {
      // Arrow from the torso; 10 frames of travel long so that walking speeds are visible.
      const cv::Point2d tip = l.direction->torso + l.direction->flow * 10.0;
      cv::arrowedLine(canvas, l.direction->torso, tip, colors::kYellow, 2, cv::LINE_AA, 0, 0.25);
    }
  }
  std::string caption = "frame " + std::to_string(frame.index) + "  people " + std::to_string(g.people.size()) +
                        "  leaders " + std::to_string(g.leaders.size());
  if (lost) caption += "  (" + std::to_string(lost) + " lost)";
  draw_caption(canvas, caption);
  // Legend along the bottom edge, each word in its colour.
  const std::pair<const char*, cv::Scalar> legend[] = {{"leader", colors::kBlue},
                                                       {"member", colors::kGreen},
                                                       {"non-member", colors::kRed},
                                                       {"potential", colors::kOrange},
                                                       {"motion", cv::Scalar(0, 160, 200)}};
  const int height = 20, y = canvas.rows - height;
  if (y <= 0) return;
  cv::rectangle(canvas, cv::Rect(0, y, canvas.cols, height), cv::Scalar(200, 200, 200), cv::FILLED);
  int x = 6;
  for (const auto& [word, color] : legend) {
    cv::putText(canvas, word, cv::Point(x, y + 14), cv::FONT_HERSHEY_SIMPLEX, 0.45, color, 1, cv::LINE_AA);
    int baseline = 0;
    x += cv::getTextSize(word, cv::FONT_HERSHEY_SIMPLEX, 0.45, 1, &baseline).width + 14;
  }
}

}  // namespace

GroupPipelineOptions GroupsJobOptions::resolved() const {
  GroupPipelineOptions o;
  o.tracking = tracking;
  o.stages = pipeline;
  o.stages.membership = membership.resolved();
  o.fps = fps;
  o.check();
  return o;
}

std::shared_ptr<const GroundPlane> GroupsJobOptions::ground_plane() const {
  if (!homography.empty() && !calibration.empty())
    throw UsageError("give --homography or --calibration, not both");
  if (!homography.empty()) return read_homography(homography);
  if (!calibration.empty()) return read_tsai_calibration(calibration);
  return nullptr;
}

void add_groups_options(CLI::App& sub, GroupsJobOptions& o) {
  add_tracker_options(sub, o.tracking);
  GroupStagesOptions& p = o.pipeline;
  add_enum_option(sub, "--roles", p.roles,
                  std::vector<std::pair<std::string, RoleMode>>{
                      {"groups", RoleMode::kGroups}, {"thesis", RoleMode::kThesis}, {"voting", RoleMode::kVoting}},
                  "Role logic: groups (trajectories, one leader per group), thesis (Table 4.1, permanent tags) "
                  "or voting (thesis rules, 50-frame votes)",
                  "groups");
  sub.add_option("--homography", o.homography,
                 "Image-to-ground homography (3x3 text, metres): group distances and speeds on the ground");
  sub.add_option("--calibration", o.calibration,
                 "Tsai camera calibration XML (PETS layout, e.g. View_001.xml) for the ground plane");
  sub.add_option("--fps", o.fps,
                 "Frame rate for times and speeds (0 = the source's; vtest.avi says 10 but was recorded at 7)")
      ->check(non_negative())->capture_default_str();
  sub.add_option("--pixels-per-metre", p.pixels_per_metre,
                 "Without a ground plane: image scale (0 = from the first boxes, a person being 1.7 m tall)")
      ->capture_default_str();
  add_group_options(sub, o.membership, GroupInput::kFrames);
  sub.add_option("--motion-threshold", p.motion.threshold, "Three-frame difference threshold (thesis: 35)")
      ->capture_default_str();
  sub.add_option("--motion-max-deviation", p.motion.max_deviation,
                 "Motion is real when the motion image's std-dev is below this (thesis: 20)")
      ->capture_default_str();
  sub.add_option("--motion-width", p.motion.work_width, "Width the motion stage works at (0 = full frame)")
      ->capture_default_str();
  sub.add_option("--true-member-distance", p.thesis.true_member_distance,
                 "thesis/voting: True Member check distance in pixels")->capture_default_str();
  sub.add_option("--close-distance", p.thesis.close_distance,
                 "thesis/voting: boxes this close (pixels) are potential members")->capture_default_str();
  sub.add_option("--prune-period", p.thesis.prune_period,
                 "thesis/voting: frames between still-box pruning passes")->capture_default_str();
  sub.add_option("--vote-period", p.thesis.vote_period, "voting: frames between votes")->capture_default_str();
  sub.add_option("--leader-hold", p.trajectory.leader_hold,
                 "groups: frames a member must walk ahead before taking the lead")->capture_default_str();
  sub.add_option("--ahead-margin", p.trajectory.ahead_margin,
                 "groups: metres further ahead a challenger must be")->capture_default_str();
  sub.add_option("--leader-min-psr", p.leader.min_psr, "Leader tracker is lost below this peak-to-sidelobe ratio")
      ->capture_default_str();
  sub.add_option("--leader-max-disagreement", p.leader.max_disagreement,
                 "Leader tracker is lost after this many frames disagreeing with the leader's detections")
      ->capture_default_str();
  sub.add_option("--leader-reacquire-frames", p.leader.reacquire_frames,
                 "Frames after a loss during which a new track may take over the leader role")
      ->capture_default_str();
  sub.add_option("--direction-window", p.direction.window, "Frames the leader direction is averaged over")
      ->capture_default_str();
}

GroupsRunStats run_groups(FrameSource& source, PeopleDetector& detector, const GroupsJobOptions& options,
                          const OutputOptions& outputs, bool write_jsonl,
                          const std::function<void(const Frame&, const GroupFrame&)>& on_frame) {
  GroupPipeline pipeline(detector, options.resolved(), options.ground_plane());
  RunSinks sinks(outputs, write_jsonl, options.fps > 0 ? options.fps : source.fps().value_or(25.0));
  Progress progress(source.frame_count(), outputs.quiet);
  GroupsRunStats stats;
  for (Frame frame; !StopOnSignal::requested() && source.read(frame);) {
    const GroupPipelineResult r = naming_frame(frame, [&] { return pipeline.process(frame); });
    ++stats.frames;
    stats.tracking_ms += r.tracking_ms;
    stats.stages.motion += r.groups.ms.motion;
    stats.stages.groups += r.groups.ms.groups;
    stats.stages.roles += r.groups.ms.roles;
    stats.stages.leader += r.groups.ms.leader;
    stats.stages.flow += r.groups.ms.flow;
    if (sinks.jsonl) sinks.jsonl->write(frame_json(frame, r.time_s, r.groups));
    if (sinks.mot) {
      for (const auto& t : r.tracks) sinks.mot->write(frame.index, t.id, t.box, 1.0);
      sinks.mot->end_frame();
    }
    if (sinks.annotated) {
      cv::Mat canvas = frame.image.clone();
      draw(canvas, frame, r.groups);
      sinks.annotated->write(frame.index, canvas);
    }
    if (on_frame) on_frame(frame, r.groups);
    progress.update(stats.frames);
  }
  sinks.note_stale();
  stats.stopped = StopOnSignal::requested();
  return stats;
}

}  // namespace bodyrec::cli
