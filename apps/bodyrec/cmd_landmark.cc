// `bodyrec landmark`: people detection (tracked with --track), then the body-contour shape model (thesis Ch3).
#include <chrono>
#include <iomanip>
#include <iostream>
#include <optional>
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
#include "stop_signal.h"
#include "tracking_job.h"

namespace bodyrec::cli {
namespace {

// One person to landmark on a frame: a detection (no id) or, with --track, a reported track.
struct Person {
  Box box;
  std::optional<double> score;  // detections only
  int id = -1;                  // tracks only
  std::optional<TrackState> state;
  std::vector<cv::Point2d> landmarks;  // empty for a lost track (not seen on this frame)
};

struct LandmarkCommand {
  SourceOptions source;
  OutputOptions outputs;
  DetectorOptions detector;
  ShapeFittingOptions fitting;
  TrackingJobOptions tracking;
  std::string shape, detector_choice = "hog";
  CLI::Option* detector_option = nullptr;
  bool track = false;

  void run() {
    if (!outputs.mot.empty() && !track) throw UsageError("landmark writes MOT output only with --track (ids)");
    if (track) tracking.check();  // before the model loads and the source opens
    if (detector_choice == "hog" && detector_option->count() > 0 && !detector.model_file.empty())
      throw UsageError("--detector hog and --model/--detector-model " + detector.model_file +
                       " name two detectors: give one");
    if (detector_choice != "hog") {
      if (!detector.model_file.empty() && detector.model_file != detector_choice)
        throw UsageError("give the fHOG model with either --detector or --model/--detector-model, not both");
      detector.model_file = detector_choice;
    }
    BodyShapeModel model(shape_model_path(shape));
    fitting.apply(model);
    auto frames = open_source(source);
    if (!track) detector.use = DetectorUse::kDetect;  // one detection per image, no sequence
    auto people = make_detector(detector, *frames);
    std::optional<DetectAndTrack> tracker;
    if (track) tracker.emplace(*people, tracking);
    RunSinks sinks(outputs, true, frames->fps().value_or(25.0));
    Progress progress(frames->frame_count(), outputs.quiet);
    Frame frame;
    int count = 0, persons = 0;
    double detect_ms = 0, fit_ms = 0;
    StopOnSignal stop;  // SIGINT/SIGTERM end a live run after its frame, outputs whole, exit 0
    while (!StopOnSignal::requested() && frames->read(frame)) {
      const auto t0 = std::chrono::steady_clock::now();
      std::vector<Person> found = tracker ? tracked(*tracker, frame) : detected(*people, frame);
      const auto t1 = std::chrono::steady_clock::now();
      const cv::Mat prepared = model.prepare(frame.image);
      for (Person& p : found) {
        if (p.state == TrackState::kLost) continue;  // its box is a prediction: nobody was seen there
        p.landmarks = model.fit(prepared, p.box);
        ++persons;
      }
      const auto t2 = std::chrono::steady_clock::now();
      detect_ms += std::chrono::duration<double, std::milli>(t1 - t0).count();
      fit_ms += std::chrono::duration<double, std::milli>(t2 - t1).count();
      write(sinks, frame, found);
      progress.update(++count);
    }
    sinks.note_stale();
    if (StopOnSignal::requested()) std::cerr << "bodyrec landmark: stopped by a signal after " << count << " frames\n";
    if (!outputs.quiet && !outputs.jsonl.empty())
      std::cerr << "bodyrec landmark: " << count << " frames, " << persons << " people landmarked, "
                << (count ? detect_ms / count : 0.0) << " ms " << (track ? "detection and tracking" : "detection")
                << " per frame, " << (persons ? fit_ms / persons : 0.0) << " ms shape fitting per person ("
                << people->describe() << ")\n";
  }

  static std::vector<Person> detected(PeopleDetector& people, const Frame& frame) {
    std::vector<Person> found;
    for (const Detection& d : people.detect(frame.image)) found.push_back({d.box, d.score, -1, std::nullopt, {}});
    return found;
  }

  static std::vector<Person> tracked(DetectAndTrack& tracker, const Frame& frame) {
    std::vector<Person> found;
    // Rounded as every sink writes boxes, so that the landmarks are fitted in the box the outputs give.
    for (const TrackedPerson& t : tracker.step(frame.index, frame.image))
      found.push_back({round_box_for_output(t.box), std::nullopt, t.id, t.state, {}});
    return found;
  }

  static void write(RunSinks& sinks, const Frame& frame, const std::vector<Person>& found) {
    nlohmann::json row = {{"frame", frame.index}, {"time", frame.time_s}, {"people", nlohmann::json::array()}};
    for (const Person& p : found) {
      nlohmann::json points = nlohmann::json::array();
      for (const auto& q : p.landmarks) points.push_back({q.x, q.y});
      nlohmann::json person;
      if (p.state) {
        person["id"] = p.id;
        person["state"] = to_string(*p.state);
      }
      person["box"] = {p.box.x, p.box.y, p.box.width, p.box.height};
      if (p.score) person["score"] = *p.score;
      person["landmarks"] = points;
      row["people"].push_back(person);
    }
    sinks.jsonl->write(row);
    if (sinks.mot) {
      for (const Person& p : found) sinks.mot->write(frame.index, p.id, p.box, 1.0);
      sinks.mot->end_frame();
    }
    if (!sinks.annotated) return;
    cv::Mat canvas = frame.image.clone();
    for (const Person& p : found) {
      std::ostringstream label;
      if (p.state) label << p.id;
      else label << std::fixed << std::setprecision(2) << *p.score;
      const cv::Scalar color = p.state ? id_color(p.id) : colors::kGreen;
      draw_labelled_box(canvas, p.box, color, label.str(), 1);
      std::vector<cv::Point> polygon;
      for (const auto& q : p.landmarks) polygon.emplace_back(cvRound(q.x), cvRound(q.y));
      cv::polylines(canvas, polygon, true, p.state ? color : colors::kYellow, 2, cv::LINE_AA);
      if (!polygon.empty()) cv::circle(canvas, polygon[0], 4, colors::kRed, cv::FILLED, cv::LINE_AA);
    }
    draw_caption(canvas, "frame " + std::to_string(frame.index) + "  people " + std::to_string(found.size()));
    sinks.annotated->write(frame.index, canvas);
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<LandmarkCommand>();
  CLI::App* sub = app.add_subcommand("landmark", "Detect people and place the body-contour landmarks on each");
  sub->footer(
      "Writes one JSON object per frame: {\"frame\":N,\"time\":S,\"people\":[{\"box\":[x,y,w,h],\"score\":s,\n"
      "\"landmarks\":[[x,y],...]}]}; --annotate draws each contour as a closed polyline (red dot = point 0).\n"
      "With --track the people are the tracker's (options of `bodyrec track`): each has \"id\" and \"state\"\n"
      "(confirmed|lost) instead of \"score\", the filtered box, and no landmarks while lost (a predicted box);\n"
      "--mot writes the tracks. A new person appears once confirmed (--min-hits detections).\n"
      "People come from --preset auto: the photo detector on still images, HOG around moving regions on video.\n"
      "The shape model is the shipped one (models/README.md) unless --shape names another.\n"
      "On a slow CPU, --no-mirror runs the network on the box alone: 20-40 % less fitting time for 0.1 points\n"
      "more error (Penn-Fudan validation: 5.61 against 5.50 % of the box height; docs/benchmarks.md).\n"
      "Example: bodyrec landmark photo.jpg --annotate out/landmarks/");
  add_source_options(*sub, command->source);
  add_shape_model_option(*sub, command->shape);
  add_shape_fitting_options(*sub, command->fitting);
  command->detector_option =
      sub->add_option("--detector", command->detector_choice,
                      "People detector: 'hog' (OpenCV HOG, options below) or a dlib fHOG FILE.svm")
          ->capture_default_str();
  CLI::Option* track = sub->add_flag(
      "--track", command->track, "Track people across frames: ids, filtered boxes, the detector every --detect-every frames");
  add_output_options(*sub, command->outputs);
  add_detector_options(*sub, command->detector, DetectorUse::kTrack);
  // The search around tracks runs only with --track.
  for (CLI::Option* option : {command->detector.o_local_margin, command->detector.o_local_height_margin})
    option->needs(track);
  for (CLI::Option* option : add_tracker_options(*sub, command->tracking)) option->needs(track);
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 33, add});

}  // namespace
}  // namespace bodyrec::cli
