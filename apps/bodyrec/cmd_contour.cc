// `bodyrec contour REC --landmarks N`: per-body outlines (thesis Ch5 CCD kernel, or OpenCV's
// findContours) and N contour landmarks with camera-space positions, as JSON lines and annotated images.
#include <chrono>
#include <cstdio>

#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/io/sinks.h"
#include "bodyrec/rgbd/contour.h"
#include "bodyrec/rgbd/recording.h"
#include "bodyrec/rgbd/segment.h"
#include "command.h"
#include "rgbd_input.h"
#include "run_sinks.h"
#include "segment_options.h"
#include "option_checks.h"

namespace bodyrec::cli {
namespace {

const cv::Scalar kBodyColors[kMaxBodies] = {{255, 128, 0}, {0, 200, 0}, {0, 200, 255},
                                            {255, 0, 255}, {255, 255, 0}, {128, 128, 255}};

double round3(double v) { return std::round(v * 1000) / 1000; }

// Depth as grey (near bright), CCD contour pixels in the body's colour, landmarks as dots, point 0 red.
cv::Mat annotate(const cv::Mat& depth, double unit, const cv::Mat& ccd, const std::vector<BodyContour>& bodies) {
  cv::Mat grey(depth.size(), CV_8U);
  for (int y = 0; y < depth.rows; ++y)
    for (int x = 0; x < depth.cols; ++x) {
      const double z = depth.at<uint16_t>(y, x) * unit;
      grey.at<uint8_t>(y, x) = z > 0 ? static_cast<uint8_t>(std::clamp(255.0 - z * 30.0, 40.0, 255.0)) : 0;
    }
  cv::Mat img;
  cv::cvtColor(grey, img, cv::COLOR_GRAY2BGR);
  for (int y = 0; y < ccd.rows; ++y)
    for (int x = 0; x < ccd.cols; ++x) {
      const uint8_t b = ccd.at<uint8_t>(y, x);
      if (b < kMaxBodies) {
        const cv::Scalar& c = kBodyColors[b];
        img.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<uint8_t>(c[0]), static_cast<uint8_t>(c[1]), static_cast<uint8_t>(c[2]));
      }
    }
  for (const auto& b : bodies)
    for (size_t i = 0; i < b.landmarks.size(); ++i)
      cv::circle(img, b.landmarks[i], i == 0 ? 4 : 2, i == 0 ? cv::Scalar(0, 0, 255) : kBodyColors[b.label], cv::FILLED,
                 cv::LINE_AA);
  return img;
}

struct ContourCommand {
  std::string recording, jsonl, annotate_path, method = "ccd";
  SegmentCliOptions seg;
  LiveCliOptions live;
  int landmarks = 180, max_frames = -1;
  bool json = false, quiet = false;

  void run() const {
    const ContourMethod m = parse_contour_method(method);
    check_input_given(recording, live);
    StopOnSignal stop;  // SIGINT/SIGTERM end a live run with its outputs whole
    RgbdInput input(recording, live);
    const RecordingMeta& meta = input.meta();
    if (!meta.streams.depth) throw InputError(input.name() + ": contour needs a depth stream");
    const bool body_index = meta.streams.body_index;
    std::optional<DepthSegmenter> segmenter;
    if (!body_index)
      segmenter.emplace(input.recording() ? make_segmenter(*input.recording(), seg) : make_segmenter(meta, seg));
    std::unique_ptr<JsonlWriter> out;
    if (!quiet || !jsonl.empty()) out = std::make_unique<JsonlWriter>(jsonl);
    std::unique_ptr<AnnotatedWriter> images;
    if (!annotate_path.empty()) images = std::make_unique<AnnotatedWriter>(annotate_path, meta.fps);
    int last_bodies = 0;
    double ms = 0;
    cv::Mat ccd;
    const FrameLoopStats stats = run_rgbd_loop(input, live, max_frames, [&](RgbdFrame& f, const FrameArrival& arrival) {
      const auto t0 = std::chrono::steady_clock::now();
      const cv::Mat labels = body_index ? f.body_index : segmenter->segment(f.depth).labels;
      ccd_contour(labels, ccd);
      const std::vector<BodyContour> bodies = body_contours(labels, f.depth, meta.depth, meta.depth_unit_m, landmarks, m);
      ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      last_bodies = static_cast<int>(bodies.size());
      if (out) {
        nlohmann::json jb = nlohmann::json::array();
        for (const auto& b : bodies) {
          nlohmann::json lm = nlohmann::json::array(), pts = nlohmann::json::array();
          for (size_t i = 0; i < b.landmarks.size(); ++i) {
            lm.push_back({round3(b.landmarks[i].x), round3(b.landmarks[i].y)});
            if (b.points[i])
              pts.push_back({round3((*b.points[i])[0]), round3((*b.points[i])[1]), round3((*b.points[i])[2])});
            else
              pts.push_back(nullptr);
          }
          jb.push_back({{"label", b.label}, {"outline_length", b.outline.size()}, {"landmarks", lm}, {"points", pts}});
        }
        nlohmann::json line = {{"frame", f.index}, {"labels", body_index ? "bodyindex" : "segment"}, {"method", method}, {"bodies", jb}};
        if (live.live()) line["dropped"] = arrival.dropped;
        out->write(line);
      }
      if (images) images->write(f.index, annotate(f.depth, meta.depth_unit_m, ccd, bodies));
    });
    if (images) note_stale_frames(images->stale_note());
    const int frames = stats.frames;
    const double per_frame = frames ? ms / frames : 0.0;
    if (!quiet || json)
      std::fprintf(stderr, "%d frames, %d bodies in the last (%s, %s); %.3f ms per frame\n", frames, last_bodies,
                   body_index ? "body index" : "depth-only segmentation", method.c_str(), per_frame);
    if (json) {
      const nlohmann::json j = {{"frames", frames}, {"bodies", last_bodies}, {"landmarks", landmarks},
                                {"labels", body_index ? "bodyindex" : "segment"}, {"ms_per_frame", per_frame},
                                {"dropped", stats.dropped}};
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<ContourCommand>();
  CLI::App* sub = app.add_subcommand("contour", "Body outlines (CCD kernel or OpenCV) and 3D contour landmarks");
  sub->add_option("REC", command->recording, "Recording with depth (body index used when present), or --sensor");
  add_live_options(*sub, command->live);
  sub->add_option("--landmarks", command->landmarks, "Landmarks per body: equal arc length, 0 at the top, clockwise")
      ->check(in_range(1, 100000))
      ->capture_default_str();
  sub->add_option("--method", command->method, "Outline: ccd (thesis cross test, traced) or opencv (findContours)")
      ->check(one_of({"ccd", "opencv"}))
      ->capture_default_str();
  sub->add_option("--jsonl", command->jsonl, "Per-frame landmarks (pixels) and points (metres) as JSON lines; default stdout");
  sub->add_option("--annotate", command->annotate_path, "Annotated images: a PNG folder, or a video (.avi/.mp4/.mkv)");
  add_segment_options(*sub, command->seg);
  sub->add_option("--max-frames", command->max_frames, "Stop after this many frames; -1 = all");
  sub->add_flag("-q,--quiet", command->quiet, "No JSON lines on stdout (unless --jsonl FILE)");
  sub->add_flag("--json", command->json, "End stdout with one JSON object (frames, bodies in the last frame, ms_per_frame, dropped)");
  sub->footer("Example: bodyrec contour rec_synth --landmarks 180 --annotate contours --jsonl contours.jsonl --json");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 54, add});

}  // namespace
}  // namespace bodyrec::cli
