// `bodyrec landmark`: people detection followed by the body-contour shape model (thesis Ch3 pipeline).
#include <chrono>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/io/annotate.h"
#include "bodyrec/io/progress.h"
#include "bodyrec/landmarks/body_shape.h"
#include "command.h"
#include "common_options.h"
#include "run_sinks.h"
#include "shape_fitting_options.h"

namespace bodyrec::cli {
namespace {

struct LandmarkCommand {
  SourceOptions source;
  OutputOptions outputs;
  DetectorOptions detector;
  ShapeFittingOptions fitting;
  std::string shape, detector_choice = "hog";

  void run() {
    if (!outputs.mot.empty()) throw UsageError("landmark writes no MOT output (use detect or track)");
    if (detector_choice != "hog") {
      if (!detector.model_file.empty() && detector.model_file != detector_choice)
        throw UsageError("give the fHOG model with either --detector or --model, not both");
      detector.model_file = detector_choice;
    }
    BodyShapeModel model(shape);
    fitting.apply(model);
    auto frames = open_source(source);
    auto people = make_detector(detector, frames->fps().has_value());
    RunSinks sinks(outputs, true, frames->fps().value_or(25.0));
    Progress progress(frames->frame_count(), outputs.quiet);
    Frame frame;
    int count = 0, persons = 0;
    double detect_ms = 0, fit_ms = 0;
    while (frames->read(frame)) {
      const auto t0 = std::chrono::steady_clock::now();
      const std::vector<Detection> detections = people->detect(frame.image);
      const auto t1 = std::chrono::steady_clock::now();
      const cv::Mat prepared = model.prepare(frame.image);
      std::vector<std::vector<cv::Point2d>> shapes;
      for (const auto& d : detections) shapes.push_back(model.fit(prepared, d.box));
      const auto t2 = std::chrono::steady_clock::now();
      detect_ms += std::chrono::duration<double, std::milli>(t1 - t0).count();
      fit_ms += std::chrono::duration<double, std::milli>(t2 - t1).count();
      persons += static_cast<int>(detections.size());

      nlohmann::json row = {{"frame", frame.index}, {"time", frame.time_s}, {"people", nlohmann::json::array()}};
      for (size_t i = 0; i < detections.size(); ++i) {
        nlohmann::json points = nlohmann::json::array();
        for (const auto& p : shapes[i]) points.push_back({p.x, p.y});
        const Box& b = detections[i].box;
        row["people"].push_back(
            {{"box", {b.x, b.y, b.width, b.height}}, {"score", detections[i].score}, {"landmarks", points}});
      }
      sinks.jsonl->write(row);
      if (sinks.annotated) {
        cv::Mat canvas = frame.image.clone();
        for (size_t i = 0; i < detections.size(); ++i) {
          std::ostringstream label;
          label << std::fixed << std::setprecision(2) << detections[i].score;
          draw_labelled_box(canvas, detections[i].box, colors::kGreen, label.str(), 1);
          std::vector<cv::Point> polygon;
          for (const auto& p : shapes[i]) polygon.emplace_back(cvRound(p.x), cvRound(p.y));
          cv::polylines(canvas, polygon, true, colors::kYellow, 2, cv::LINE_AA);
          if (!polygon.empty()) cv::circle(canvas, polygon[0], 4, colors::kRed, cv::FILLED, cv::LINE_AA);
        }
        draw_caption(canvas, "frame " + std::to_string(frame.index) + "  people " + std::to_string(detections.size()));
        sinks.annotated->write(frame.index, canvas);
      }
      progress.update(++count);
    }
    if (!outputs.quiet && !outputs.jsonl.empty())
      std::cerr << "bodyrec landmark: " << count << " frames, " << persons << " people, "
                << (count ? detect_ms / count : 0.0) << " ms detection per frame, "
                << (persons ? fit_ms / persons : 0.0) << " ms shape fitting per person (" << people->describe()
                << ")\n";
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<LandmarkCommand>();
  CLI::App* sub = app.add_subcommand("landmark", "Detect people and place the body-contour landmarks on each");
  sub->footer(
      "Writes one JSON object per frame: {\"frame\":N,\"time\":S,\"people\":[{\"box\":[x,y,w,h],\"score\":s,\n"
      "\"landmarks\":[[x,y],...]}]}; --annotate draws each contour as a closed polyline (red dot = point 0).\n"
      "For unrelated still images use --motion off (the default HOG preset searches moving regions in video).\n"
      "On a slow CPU, --no-mirror runs the network on the box alone: 20-40 % less fitting time for 0.1 points\n"
      "more error (Penn-Fudan validation: 5.61 against 5.50 % of the box height; docs/benchmarks.md).\n"
      "Example: bodyrec landmark photos/ --shape out/shape.dat --detector out/detector.svm --annotate out/landmarks");
  add_source_options(*sub, command->source);
  sub->add_option("--shape", command->shape, "Shape model (bodyrec train-shape)")->required();
  add_shape_fitting_options(*sub, command->fitting);
  sub->add_option("--detector", command->detector_choice,
                  "People detector: 'hog' (OpenCV HOG, options below) or a dlib fHOG FILE.svm")
      ->capture_default_str();
  add_output_options(*sub, command->outputs);
  add_detector_options(*sub, command->detector);
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 33, add});

}  // namespace
}  // namespace bodyrec::cli
