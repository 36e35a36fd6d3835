// Options shared by several subcommands: where frames come from, where results go, which detector.
#pragma once

#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "bodyrec/detection/hog_people_detector.h"
#include "bodyrec/detection/people_detector.h"
#include "bodyrec/io/frame_source.h"

namespace bodyrec::cli {

// SOURCE (positional: video, image, directory or glob), --camera, --start, --max-frames, --every.
// With `source_flag`, the path is the option --source instead of a positional argument.
void add_source_options(CLI::App& sub, SourceOptions& options, bool source_flag = false);

struct OutputOptions {
  std::string jsonl;     // "" = stdout
  std::string annotate;  // "" = none; .avi/.mp4/.mkv/.mov = video, else a PNG folder
  std::string mot;       // "" = none
  bool quiet = false;
};

// --jsonl, --annotate, --mot, --quiet.
void add_output_options(CLI::App& sub, OutputOptions& options);

// Detector choice and every HOG parameter; explicitly given options override the preset's values.
struct DetectorOptions {
  std::string preset = "auto";  // auto: photo for still images, default for videos and cameras
  std::string model_file;  // dlib fHOG .svm; replaces HOG when given
  double fhog_upsample = 1.0, fhog_threshold = 0.0;
  std::string hog_model = "default";
  double hit_threshold = 0, scale = 0, resize = 0, nms_iou = 0.4, motion_margin = 0;
  double local_region_margin = HogOptions{}.local_region_margin, local_height_margin = HogOptions{}.local_height_margin;
  int win_stride = 0, padding = 0, group_threshold = 0, levels = 0, adapt_after = 0;
  std::vector<int> roi;
  std::string motion = "preset";  // "on", "off" or "preset"
  std::vector<CLI::Option*> given;  // filled by add_detector_options
  CLI::Option *o_hit = nullptr, *o_stride = nullptr, *o_padding = nullptr, *o_scale = nullptr,
              *o_group = nullptr, *o_resize = nullptr, *o_levels = nullptr, *o_hog_model = nullptr,
              *o_adapt = nullptr, *o_motion_margin = nullptr;
};

void add_detector_options(CLI::App& sub, DetectorOptions& options);

// Builds the detector; throws UsageError for inconsistent options, InputError for a bad model file.
// `consecutive_frames` says the frames come from one video or camera: motion regions (when the preset
// or --motion asks for them) only make sense then, so for unrelated images they are off unless
// --motion on is given.
std::unique_ptr<PeopleDetector> make_detector(const DetectorOptions& options, bool consecutive_frames = true);

}  // namespace bodyrec::cli
