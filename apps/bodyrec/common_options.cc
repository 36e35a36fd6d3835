#include "common_options.h"

#include "bodyrec/core/error.h"
#include "bodyrec/detection/dpm_people_detector.h"
#include "bodyrec/detection/fhog_detector.h"
#include "bodyrec/detection/foreground_detector.h"
#include "bodyrec/detection/hog_people_detector.h"
#include "enum_option.h"
#include "option_checks.h"

namespace bodyrec::cli {

void add_source_options(CLI::App& sub, SourceOptions& o, bool source_flag) {
  const char* help = "Input: a video file, an image, a directory of images (sorted by name) or a glob";
  if (source_flag)
    sub.add_option("--source", o.path, help);
  else
    sub.add_option("source", o.path, help);
  sub.add_option("--camera", o.camera, "Read a live camera (V4L2 index) instead of a file; -1 = none");
  sub.add_option("--start", o.start, "First frame index to process");
  sub.add_option("--max-frames", o.max_frames, "Process at most this many frames; -1 = all");
  sub.add_option("--every", o.every, "Process every Nth frame")->check(positive());
}

void add_output_options(CLI::App& sub, OutputOptions& o) {
  sub.add_option("--jsonl", o.jsonl, "Write JSON Lines (one object per frame) to FILE; default stdout");
  sub.add_option("--annotate", o.annotate,
                 "Write annotated frames: a video if it ends in .avi/.mp4/.mkv/.mov, else a PNG folder");
  sub.add_option("--mot", o.mot, "Write MOTChallenge text (frame,id,x,y,w,h,score,-1,-1,-1; 1-based)");
  sub.add_flag("--quiet,-q", o.quiet, "No progress line on stderr");
}

void add_detector_options(CLI::App& sub, DetectorOptions& o, DetectorUse use, const std::string& model_flag) {
  o.use = use;
  add_enum_option(sub, "--preset", o.preset,
                  std::vector<std::pair<std::string, DetectorPreset>>{{"auto", DetectorPreset::kAuto},
                                                                      {"default", DetectorPreset::kDefault},
                                                                      {"photo", DetectorPreset::kPhoto},
                                                                      {"foreground", DetectorPreset::kForeground},
                                                                      {"thesis", DetectorPreset::kThesis},
                                                                      {"opencv", DetectorPreset::kOpenCv}},
                  "Detector preset: 'auto' (photo for still images, default for videos and cameras, and for image "
                  "folders and globs when the command tracks), "
                  "'default' (HOG tuned for video: motion regions, people 60-140 px, stride 8), "
                  "'photo' (still photos, people of any size: OpenCV's DPM with the INRIA person model), "
                  "'foreground' (one static camera's video, camera or image sequence of at least " +
                      std::to_string(ForegroundOptions{}.warmup_frames + 1) +
                      " frames: people as foreground blobs of background subtraction, a few ms per frame; who "
                      "stands still for long fades into the background), "
                  "'thesis' (HOG: hit -0.2, stride 12, padding 16, scale 1.05, group 2, whole frame at original "
                  "size) or 'opencv' (HOG as OpenCV's peopledetect sample: hit 0, stride 8, no padding, group 2)",
                  "auto");
  // --detector-model is the one name every command takes (reid's --model is its matcher's).
  const std::string names = model_flag == "--detector-model" ? model_flag : model_flag + ",--detector-model";
  sub.add_option(names, o.model_file, "Use a dlib fHOG detector from FILE.svm instead of HOG");
  sub.add_option("--fhog-upsample", o.fhog_upsample, "fHOG: image scale factor before detection");
  sub.add_option("--fhog-threshold", o.fhog_threshold, "fHOG: added to the model's threshold");
  const std::string p = " (default: the preset's value)";
  o.o_hog_model = sub.add_option("--hog-model", o.hog_model, "HOG SVM: 'default' (64x128) or 'daimler' (48x96)")
                      ->check(one_of({"default", "daimler"}));
  o.o_hit = sub.add_option("--hit-threshold", o.hit_threshold, "HOG: SVM score threshold" + p);
  o.o_stride = sub.add_option("--win-stride", o.win_stride, "HOG: window stride in pixels" + p);
  o.o_padding = sub.add_option("--padding", o.padding, "HOG: padding in pixels" + p);
  o.o_scale = sub.add_option("--scale", o.scale, "HOG: pyramid scale step" + p);
  o.o_group = sub.add_option("--group-threshold", o.group_threshold, "HOG: grouping threshold" + p);
  o.o_resize = sub.add_option("--resize", o.resize, "HOG: image scale factor before detection" + p);
  o.o_levels = sub.add_option("--levels", o.levels, "HOG: pyramid levels searched" + p);
  o.o_adapt = sub.add_option("--adapt-after", o.adapt_after,
                             "HOG with motion regions: after N confident detections, search each region only at "
                             "the person heights the scene shows there (0 = off)" + p);
  o.o_motion_margin = sub.add_option("--motion-margin", o.motion_margin,
                                     "Motion regions grow by this fraction of their size on every side" + p);
  for (CLI::Option* opt : {o.o_hit, o.o_stride, o.o_padding, o.o_scale, o.o_group, o.o_resize, o.o_levels, o.o_adapt,
                           o.o_motion_margin})
    opt->default_str("preset");
  sub.add_option("--roi", o.roi, "Only search this region: X Y W H (frame pixels)")->expected(4);
  add_enum_option(sub, "--motion", o.motion,
                  std::vector<std::pair<std::string, MotionChoice>>{
                      {"on", MotionChoice::kOn}, {"off", MotionChoice::kOff}, {"preset", MotionChoice::kPreset}},
                  "Search only around moving regions: on, off, or as the preset says", "preset");
  o.o_nms = sub.add_option("--nms-iou", o.nms_iou,
                           "Non-maximum suppression IoU threshold (HOG, photo and fHOG detectors)")
                ->capture_default_str();
  if (use == DetectorUse::kDetect) return;
  o.o_local_margin = sub.add_option("--local-margin", o.local_region_margin,
                                    "HOG search around a track (frames between full detections): the window grows "
                                    "by this fraction of its size on every side")
                         ->capture_default_str();
  o.o_local_height_margin =
      sub.add_option("--local-height-margin", o.local_height_margin,
                     "HOG search around a track: heights within this fraction of the track's are searched")
          ->capture_default_str();
}

std::unique_ptr<PeopleDetector> make_detector(const DetectorOptions& o, bool consecutive_frames,
                                              std::optional<int> frame_count) {
  // The library reads an empty rectangle as "no region", the whole frame: an empty --roi is a mistake.
  if (o.roi.size() == 4 && (o.roi[2] <= 0 || o.roi[3] <= 0))
    throw UsageError("--roi: " + std::to_string(o.roi[2]) + "x" + std::to_string(o.roi[3]) +
                     " is not a region (width and height must be positive)");
  auto given = [](const CLI::Option* opt) { return opt && opt->count() > 0; };
  // Options only HOG reads.
  const std::vector<const CLI::Option*> hog_only = {o.o_hog_model, o.o_hit,    o.o_stride,       o.o_padding,
                                                    o.o_scale,     o.o_group,  o.o_resize,       o.o_levels,
                                                    o.o_adapt,     o.o_motion_margin, o.o_local_margin,
                                                    o.o_local_height_margin};
  // Refused rather than ignored when another detector runs; `instead` says which.
  const auto refuse_hog_options = [&](const std::string& instead) {
    for (const CLI::Option* opt : hog_only)
      if (given(opt)) throw UsageError(opt->get_name() + " is a HOG option; " + instead);
    if (o.roi.size() == 4) throw UsageError("--roi is a HOG option; " + instead);
  };
  if (!o.model_file.empty()) {
    if (o.preset != DetectorPreset::kAuto)
      throw UsageError("a dlib fHOG model is its own detector: --preset takes no value with it");
    refuse_hog_options("a dlib fHOG model takes none");
    if (o.motion != MotionChoice::kPreset) throw UsageError("--motion is a HOG option; a dlib fHOG model takes none");
    FhogOptions f;
    f.model_path = o.model_file;
    f.upsample = o.fhog_upsample;
    f.adjust_threshold = o.fhog_threshold;
    f.nms_iou = o.nms_iou;
    return std::make_unique<FhogDetector>(f);
  }
  DetectorPreset preset = o.preset;
  if (preset == DetectorPreset::kAuto) {
    // Still images have no motion to narrow the search and their people may be any size: the photo
    // detector, unless a HOG option says HOG is wanted.
    bool hog = o.roi.size() == 4 || o.motion == MotionChoice::kOn;
    for (const CLI::Option* opt : hog_only) hog |= given(opt);
    preset = consecutive_frames || hog ? DetectorPreset::kDefault : DetectorPreset::kPhoto;
  }
  if (preset == DetectorPreset::kPhoto || preset == DetectorPreset::kForeground) {
    const bool photo = preset == DetectorPreset::kPhoto;
    const std::string name = photo ? "photo" : "foreground";
    const std::string which = photo ? "the DPM detector" : "background subtraction";
    refuse_hog_options("--preset " + name + " uses " + which);
    if (o.motion == MotionChoice::kOn)
      throw UsageError("--motion on needs a HOG preset; --preset " + name + " uses " + which);
  }
  if (preset == DetectorPreset::kForeground) {
    // Blobs of background subtraction do not overlap: there is nothing to suppress.
    if (given(o.o_nms)) throw UsageError("--nms-iou: --preset foreground's blobs do not overlap, nothing is suppressed");
    const ForegroundOptions f;
    if (frame_count && *frame_count <= f.warmup_frames)
      throw UsageError("--preset foreground learns the background for " + std::to_string(f.warmup_frames) +
                       " frames before it reports anyone, and the input has " + std::to_string(*frame_count) +
                       ": give a longer sequence, or --preset photo for still images");
    // Asked for by name, so an image folder is taken as one static camera's frames in order.
    return std::make_unique<ForegroundPeopleDetector>(f);
  }
  if (preset == DetectorPreset::kPhoto) {
    DpmOptions d = dpm_photo_preset();
    d.nms_iou = o.nms_iou;
    return std::make_unique<DpmPeopleDetector>(d);
  }
  const HogPreset hog = preset == DetectorPreset::kThesis   ? HogPreset::kThesis
                        : preset == DetectorPreset::kOpenCv ? HogPreset::kOpenCv
                                                            : HogPreset::kDefault;
  HogOptions h = hog_preset(hog);
  if (given(o.o_hog_model)) h.model = *parse_hog_model(o.hog_model);
  if (given(o.o_hit)) h.hit_threshold = o.hit_threshold;
  if (given(o.o_stride)) h.win_stride = o.win_stride;
  if (given(o.o_padding)) h.padding = o.padding;
  if (given(o.o_scale)) h.scale = o.scale;
  if (given(o.o_group)) h.group_threshold = o.group_threshold;
  if (given(o.o_resize)) h.resize = o.resize;
  if (given(o.o_levels)) h.levels = o.levels;
  if (given(o.o_resize) || given(o.o_levels)) h.min_height = h.max_height = 0;  // a custom range: no adaptation
  if (given(o.o_adapt)) h.adapt_after = o.adapt_after;
  if (given(o.o_motion_margin)) h.motion.margin = o.motion_margin;
  if (o.roi.size() == 4) h.roi = cv::Rect(o.roi[0], o.roi[1], o.roi[2], o.roi[3]);
  if (o.motion != MotionChoice::kPreset) h.motion_roi = o.motion == MotionChoice::kOn;
  else if (!consecutive_frames) h.motion_roi = false;
  h.nms_iou = o.nms_iou;
  h.local_region_margin = o.local_region_margin;
  h.local_height_margin = o.local_height_margin;
  return std::make_unique<HogPeopleDetector>(h);
}

std::unique_ptr<PeopleDetector> make_detector(const DetectorOptions& options, const FrameSource& source) {
  const std::optional<int> frames = source.frame_count();
  const bool sequence = options.use == DetectorUse::kTrack && frames.value_or(2) > 1;
  return make_detector(options, source.fps().has_value() || sequence, frames);
}

}  // namespace bodyrec::cli
