// The plain-camera side of `reid` and `eval reid-stream`: which inputs are colour-only (a video, an image
// folder or glob, `--camera N`, or a recording with `--colour-only`) and how their people are found
// (detector and tracker, `track`'s options), cut out (body mask) and placed (calibration): the pieces of a
// ColourReidPipeline (reid/colour_reid_pipeline.h).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bodyrec/detection/people_detector.h"
#include "bodyrec/io/frame_source.h"
#include "bodyrec/landmarks/body_shape.h"
#include "bodyrec/reid/colour_reid_pipeline.h"
#include "common_options.h"
#include "tracking_job.h"

namespace bodyrec::cli {

enum class PeopleFrom { kForeground, kHog };  // --detector
enum class MaskFrom { kForeground, kShape };  // --body-mask

struct ColourCliOptions {
  bool colour_only = false;  // --colour-only: a recording's colour frames alone
  int camera = -1;           // --camera N
  PeopleFrom people = PeopleFrom::kForeground;
  DetectorOptions detector;  // HOG preset and options; --detector-model: a dlib fHOG model instead
  TrackingJobOptions tracking = ColourReidOptions::default_tracking();
  MaskFrom mask = MaskFrom::kForeground;
  std::string shape_model;   // --shape-model (bodyrec train-shape) for --body-mask shape
  std::string calibration, homography;
  int history = ForegroundOptions{}.history;  // --background-history
  double image_fps = 25;     // --fps: the frame rate of an image sequence (its frames carry no times)
  std::vector<const CLI::Option*> plain_camera_only;  // the options an RGB-D input does not read
};

// UsageError naming the first of options.plain_camera_only that was given: the input (`what`) is an RGB-D
// recording or sensor, whose path does not read them.
void refuse_plain_camera_options(const ColourCliOptions& options, const std::string& what);

// --colour-only, (with `camera`) --camera, --detector, --detector-model and the HOG options, the tracker's
// options, --body-mask, --shape-model, --calibration, --homography, --background-history, --fps; all in the help
// group "Plain camera".
void add_colour_options(CLI::App& sub, ColourCliOptions& options, bool camera = true);

// Whether the run is colour-only: --camera, --colour-only, or an input that is neither a recording folder
// (with meta.json) nor an NTU .skeleton file.
bool is_colour_input(const std::string& path, const ColourCliOptions& options);

struct ColourInput {
  std::unique_ptr<FrameSource> frames;  // a video, images or a camera; null: the recording's colour frames
  std::unique_ptr<PeopleDetector> detector;
  std::unique_ptr<ColourGround> ground;
  std::unique_ptr<BodyShapeModel> shape;
  std::unique_ptr<BodyMasker> masker;  // null: the foreground (the pipeline's default)
  ColourReidOptions options;
  bool video = false;  // frames from a file with its own rate (--realtime applies)
  // An image sequence: its frames have no times, so frame N is placed at N / image_fps seconds (walking
  // directions and leaving are measured in time). Unset for videos and cameras.
  std::optional<double> image_fps;
};

// Opens what a colour run needs before any output is created. `path` is the input (ignored with --camera;
// a recording with --colour-only: no frame source is opened, the caller reads the recording). UsageError
// for conflicting options; InputError for unreadable inputs, models or calibrations.
std::unique_ptr<ColourInput> open_colour_input(const std::string& path, const ColourCliOptions& options,
                                               bool use_faces, const OnlineReidOptions& reid);

}  // namespace bodyrec::cli
