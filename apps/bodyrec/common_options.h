// Options shared by several subcommands: where frames come from, where results go, which detector.
#pragma once

#include <memory>
#include <optional>
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

// --preset: which detector, and for HOG its parameter set.
enum class DetectorPreset {
  kAuto,        // photo for unrelated still images, default for videos and cameras
  kDefault,     // HOG tuned for video (hog_preset(HogPreset::kDefault))
  kPhoto,       // OpenCV's DPM with the INRIA person model (dpm_photo_preset())
  kForeground,  // background subtraction on one static camera (ForegroundPeopleDetector)
  kThesis,      // HOG as the thesis called it
  kOpenCv,      // HOG as OpenCV's peopledetect sample
};

// --motion: HOG's search around moving regions.
enum class MotionChoice { kPreset, kOn, kOff };

// What a command does with its detector: a tracking command also searches around its tracks between full
// detections (--local-margin, --local-height-margin) and reads any input as one sequence; a detecting one
// does neither, so has no such options.
enum class DetectorUse { kDetect, kTrack };

// Detector choice and every HOG parameter; explicitly given options override the preset's values.
struct DetectorOptions {
  DetectorPreset preset = DetectorPreset::kAuto;
  std::string model_file;  // dlib fHOG .svm; replaces HOG when given
  double fhog_upsample = 1.0, fhog_threshold = 0.0;
  std::string hog_model = "default";
  double hit_threshold = 0, scale = 0, resize = 0, nms_iou = 0.4, motion_margin = 0;
  double local_region_margin = HogOptions{}.local_region_margin, local_height_margin = HogOptions{}.local_height_margin;
  int win_stride = 0, padding = 0, group_threshold = 0, levels = 0, adapt_after = 0;
  std::vector<int> roi;
  MotionChoice motion = MotionChoice::kPreset;
  std::vector<CLI::Option*> given;  // filled by add_detector_options
  DetectorUse use = DetectorUse::kDetect;  // set by add_detector_options
  CLI::Option *o_hit = nullptr, *o_stride = nullptr, *o_padding = nullptr, *o_scale = nullptr,
              *o_group = nullptr, *o_resize = nullptr, *o_levels = nullptr, *o_hog_model = nullptr,
              *o_adapt = nullptr, *o_motion_margin = nullptr, *o_nms = nullptr, *o_local_margin = nullptr,
              *o_local_height_margin = nullptr;
};

// `model_flag` names the fHOG model option: `--model`, also taken as `--detector-model` (the name every command
// shares); a command whose --model is something else gives "--detector-model" alone.
void add_detector_options(CLI::App& sub, DetectorOptions& options, DetectorUse use,
                          const std::string& model_flag = "--model");

// Builds the detector; throws UsageError for inconsistent options, InputError for a bad model file.
// `consecutive_frames` says the frames come from one video or camera: motion regions (when the preset
// or --motion asks for them) only make sense then, so for unrelated images they are off unless
// --motion on is given. `frame_count`, when known, is how many frames the detector will see: fewer than
// the foreground preset's warm-up is a usage error (it would report nobody).
std::unique_ptr<PeopleDetector> make_detector(const DetectorOptions& options, bool consecutive_frames = true,
                                              std::optional<int> frame_count = std::nullopt);

// The same for the frames of `source`, with its frame count if known. A video or a camera is consecutive
// frames; so are the images of a folder or glob (more than one) when the command tracks (`options.use`):
// tracking reads them as one sequence, so --preset auto picks the video preset for them as for a video.
std::unique_ptr<PeopleDetector> make_detector(const DetectorOptions& options, const FrameSource& source);

}  // namespace bodyrec::cli
