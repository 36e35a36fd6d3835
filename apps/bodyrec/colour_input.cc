#include "colour_input.h"

#include "bodyrec/core/error.h"
#include "bodyrec/detection/foreground_detector.h"
#include "bodyrec/rgbd/recording.h"
#include "enum_option.h"
#include "option_checks.h"
#include "shape_body_mask.h"

namespace bodyrec::cli {

void add_colour_options(CLI::App& sub, ColourCliOptions& o, bool camera) {
  const std::string group = "Plain camera (a video, images, --camera, or --colour-only)";
  const std::size_t before = sub.get_options().size();
  sub.add_flag("--colour-only", o.colour_only,
               "Use a recording's colour frames alone, as a plain camera would see them (depth, body index and "
               "skeletons ignored)");
  if (camera) sub.add_option("--camera", o.camera, "Read a live camera (V4L2 index) instead of a file; -1 = none");
  add_enum_option(sub, "--detector", o.people,
                  std::vector<std::pair<std::string, PeopleFrom>>{{"foreground", PeopleFrom::kForeground},
                                                                  {"hog", PeopleFrom::kHog}},
                  "People: foreground (background subtraction, for a static camera) or hog (the HOG detector "
                  "with --preset and the HOG options; a dlib fHOG model with --detector-model)",
                  "foreground");
  add_detector_options(sub, o.detector, DetectorUse::kTrack, "--detector-model");
  add_tracker_options(sub, o.tracking);
  add_enum_option(sub, "--body-mask", o.mask,
                  std::vector<std::pair<std::string, MaskFrom>>{{"foreground", MaskFrom::kForeground},
                                                                {"shape", MaskFrom::kShape}},
                  "What cuts each person out of their box: foreground (background subtraction inside the box) or "
                  "shape (the outline of --shape-model, filled)",
                  "foreground");
  sub.add_option("--shape-model", o.shape_model, "Body shape model (bodyrec train-shape) for --body-mask shape");
  sub.add_option("--calibration", o.calibration,
                 "Tsai camera calibration (PETS 2009 XML): walking directions on the ground, and statures");
  sub.add_option("--homography", o.homography,
                 "Image -> ground homography (9 numbers, metres): walking directions on the ground, no statures");
  sub.add_option("--background-history", o.history,
                 "Frames of the background model (foreground detector and masks): someone still this long fades "
                 "into the background")
      ->check(in_range(10, 100000))
      ->capture_default_str();
  sub.add_option("--fps", o.image_fps,
                 "Frame rate of an image sequence, whose files carry no times: image N is at N / fps seconds "
                 "(walking directions and leaving are measured in time); videos and cameras have their own")
      ->check(in_range(0.1, 1000.0))
      ->capture_default_str();
  const std::vector<CLI::Option*> all = sub.get_options();
  for (std::size_t i = before; i < all.size(); ++i) {
    all[i]->group(group);
    if (!all[i]->check_lname("colour-only") && !all[i]->check_lname("camera")) o.plain_camera_only.push_back(all[i]);
  }
}

void refuse_plain_camera_options(const ColourCliOptions& options, const std::string& what) {
  for (const CLI::Option* opt : options.plain_camera_only)
    if (opt->count() > 0)
      throw UsageError(opt->get_name() + " is for plain-camera input (a video, images, --camera or --colour-only); " +
                       what + " is read as RGB-D");
}

bool is_colour_input(const std::string& path, const ColourCliOptions& options) {
  if (options.camera >= 0 || options.colour_only) return true;
  if (path.size() > 9 && path.compare(path.size() - 9, 9, ".skeleton") == 0) return false;
  return !is_recording_directory(path);
}

std::unique_ptr<ColourInput> open_colour_input(const std::string& path, const ColourCliOptions& o, bool use_faces,
                                               const OnlineReidOptions& reid) {
  if (!o.calibration.empty() && !o.homography.empty())
    throw UsageError("--calibration and --homography: give one (a calibration maps the ground too)");
  if (o.mask == MaskFrom::kShape && o.shape_model.empty()) throw UsageError("--body-mask shape needs --shape-model");
  if (o.mask != MaskFrom::kShape && !o.shape_model.empty())
    throw UsageError("--shape-model is used by --body-mask shape only");
  if (o.people == PeopleFrom::kForeground && !o.detector.model_file.empty())
    throw UsageError("--detector-model is a HOG-family detector: give --detector hog with it");
  if (o.people == PeopleFrom::kHog && o.detector.preset == DetectorPreset::kForeground)
    throw UsageError("--preset foreground is background subtraction: give --detector foreground instead of hog");
  auto in = std::make_unique<ColourInput>();
  ColourReidOptions& co = in->options;
  co.tracking = o.tracking;
  co.reid = reid;
  co.views.use_faces = use_faces;
  co.foreground.history = o.history;
  co.check();
  if (!o.colour_only) {
    SourceOptions s;
    s.path = o.camera >= 0 ? "" : path;
    s.camera = o.camera;
    in->frames = open_source(s);
    in->video = o.camera < 0 && in->frames->fps().has_value();
    if (o.camera < 0 && !in->frames->fps()) in->image_fps = o.image_fps;
  }
  if (o.people == PeopleFrom::kForeground) {
    ForegroundOptions f;
    f.history = o.history;
    in->detector = std::make_unique<ForegroundPeopleDetector>(f);
  } else {
    in->detector = make_detector(o.detector, true);
  }
  if (!o.calibration.empty()) in->ground = read_colour_ground(o.calibration, GroundFile::kCalibration);
  if (!o.homography.empty()) in->ground = read_colour_ground(o.homography, GroundFile::kHomography);
  if (o.mask == MaskFrom::kShape) {
    in->shape = std::make_unique<BodyShapeModel>(o.shape_model);
    in->masker = std::make_unique<ShapeBodyMask>(*in->shape);
  }
  return in;
}

}  // namespace bodyrec::cli
