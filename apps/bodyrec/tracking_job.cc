#include "tracking_job.h"

#include <chrono>
#include <map>
#include <optional>

#include "bodyrec/core/error.h"
#include "bodyrec/io/annotate.h"
#include "bodyrec/io/progress.h"
#include "enum_option.h"
#include "frame_errors.h"
#include "option_checks.h"
#include "run_sinks.h"
#include "stop_signal.h"

namespace bodyrec::cli {
std::vector<CLI::Option*> add_tracker_options(CLI::App& sub, TrackingJobOptions& o) {
  const size_t before = sub.get_options().size();
  TrackerOptions& t = o.tracker;
  sub.add_option("--detect-every", o.detect_every,
                 "Run the full detector on every Nth frame (see --between for the frames in between)")
      ->check(positive())->capture_default_str();
  add_enum_option(sub, "--between", o.between,
                  std::vector<std::pair<std::string, BetweenDetections>>{{"local", BetweenDetections::kLocal},
                                                                         {"predict", BetweenDetections::kPredict}},
                  "Frames between full detections: 'local' searches only around the tracks, 'predict' only "
                  "carries them by their Kalman prediction",
                  "local");
  sub.add_option("--min-hits", t.min_hits, "Detections needed to confirm a track")->capture_default_str();
  sub.add_option("--max-age", t.max_age, "Frames a track survives without detections (occlusions)")
      ->capture_default_str();
  sub.add_option("--coast", t.coast_frames, "Frames a lost track is still reported at its predicted box")
      ->capture_default_str();
  sub.add_option("--iou-gate", t.iou_gate, "Least IoU between a detection and a predicted track box")
      ->capture_default_str();
  sub.add_option("--distance-gate", t.distance_gate,
                 "Second pass: largest centre distance, in predicted box heights (0 = off)")
      ->capture_default_str();
  sub.add_option("--size-gate", t.size_gate, "Second pass: least height ratio of detection and track")
      ->capture_default_str();
  sub.add_option("--min-score", t.min_score, "Ignore detections scoring below this")->capture_default_str();
  sub.add_option("--new-track-score", t.new_track_score,
                 "Least detector score to start a track (weaker ones only extend tracks)")
      ->capture_default_str();
  sub.add_option("--kf-position-noise", t.noise.position, "Kalman position noise per frame, times box height")
      ->check(positive())
      ->capture_default_str();
  sub.add_option("--kf-velocity-noise", t.noise.velocity, "Kalman velocity noise per frame, times box height")
      ->check(positive())
      ->capture_default_str();
  sub.add_option("--kf-measurement-noise", t.noise.measurement, "Kalman measurement noise, times box height")
      ->check(positive())
      ->capture_default_str();
  const std::vector<CLI::Option*> all = sub.get_options();  // in the order they were added
  return {all.begin() + static_cast<std::ptrdiff_t>(before), all.end()};
}

TrackingRunStats run_tracking(FrameSource& source, PeopleDetector& detector, const TrackingJobOptions& options,
                              const OutputOptions& outputs, bool write_jsonl,
                              const std::function<void(const Frame&, const std::vector<TrackedPerson>&)>& on_frame) {
  DetectAndTrack tracking(detector, options);
  RunSinks sinks(outputs, write_jsonl, source.fps().value_or(25.0));
  auto& [jsonl, mot, annotated] = sinks;

  Progress progress(source.frame_count(), outputs.quiet);
  TrackingRunStats stats;
  Frame frame;
  while (!StopOnSignal::requested() && source.read(frame)) {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<TrackedPerson> tracks = naming_frame(frame, [&] { return tracking.step(frame.index, frame.image); });
    const bool detect = tracking.last_was_full();
    if (detect) ++stats.detected_frames;
    // Same precision as every sink writes, so results re-read from a file score the same.
    for (auto& t : tracks) t.box = round_box_for_output(t.box);
    stats.processing_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ++stats.frames;

    if (jsonl) {
      nlohmann::json row = {{"frame", frame.index}, {"time", frame.time_s}, {"tracks", nlohmann::json::array()}};
      for (const auto& t : tracks)
        row["tracks"].push_back(
            {{"id", t.id}, {"box", {t.box.x, t.box.y, t.box.width, t.box.height}}, {"state", to_string(t.state)}});
      jsonl->write(row);
    }
    if (mot) {
      for (const auto& t : tracks) mot->write(frame.index, t.id, t.box, 1.0);
      mot->end_frame();
    }
    if (annotated) {
      cv::Mat canvas = frame.image.clone();
      for (const auto& t : tracks)
        draw_labelled_box(canvas, t.box, id_color(t.id), std::to_string(t.id), t.state == TrackState::kLost ? 1 : 2);
      draw_caption(canvas, "frame " + std::to_string(frame.index) + "  tracks " + std::to_string(tracks.size()) +
                               (detect ? "" : options.between == BetweenDetections::kLocal ? "  (searched near tracks)" : "  (predicted)"));
      annotated->write(frame.index, canvas);
    }
    if (on_frame) on_frame(frame, tracks);
    progress.update(stats.frames);
  }
  sinks.note_stale();
  stats.stopped = StopOnSignal::requested();
  return stats;
}

}  // namespace bodyrec::cli
