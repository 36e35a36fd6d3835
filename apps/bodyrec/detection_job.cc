#include "detection_job.h"

#include <chrono>
#include <iomanip>
#include <optional>
#include <sstream>

#include "bodyrec/io/annotate.h"
#include "bodyrec/io/progress.h"
#include "frame_errors.h"
#include "run_sinks.h"
#include "stop_signal.h"

namespace bodyrec::cli {

DetectionRunStats run_detection(FrameSource& source, PeopleDetector& detector, const OutputOptions& outputs,
                                bool write_jsonl,
                                const std::function<void(const Frame&, const std::vector<Detection>&)>& on_frame) {
  RunSinks sinks(outputs, write_jsonl, source.fps().value_or(25.0));
  auto& [jsonl, mot, annotated] = sinks;

  Progress progress(source.frame_count(), outputs.quiet);
  DetectionRunStats stats;
  Frame frame;
  while (!StopOnSignal::requested() && source.read(frame)) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<Detection> detections = naming_frame(frame, [&] { return detector.detect(frame.image); });
    stats.detector_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ++stats.frames;

    if (jsonl) {
      nlohmann::json row = {{"frame", frame.index}, {"time", frame.time_s}, {"detections", nlohmann::json::array()}};
      for (const auto& d : detections)
        row["detections"].push_back({{"box", {d.box.x, d.box.y, d.box.width, d.box.height}}, {"score", d.score}});
      jsonl->write(row);
    }
    if (mot) {
      for (const auto& d : detections) mot->write(frame.index, -1, d.box, d.score);
      mot->end_frame();
    }
    if (annotated) {
      cv::Mat canvas = frame.image.clone();
      for (const auto& d : detections) {
        std::ostringstream label;
        label << std::fixed << std::setprecision(2) << d.score;
        draw_labelled_box(canvas, d.box, colors::kGreen, label.str());
      }
      draw_caption(canvas, "frame " + std::to_string(frame.index) + "  people " + std::to_string(detections.size()));
      annotated->write(frame.index, canvas);
    }
    if (on_frame) on_frame(frame, detections);
    progress.update(stats.frames);
  }
  sinks.note_stale();
  stats.stopped = StopOnSignal::requested();
  return stats;
}

}  // namespace bodyrec::cli
