#include "orient_job.h"

#include <map>

#include "bodyrec/core/error.h"
#include "bodyrec/rgbd/ntu_skeleton.h"
#include "enum_option.h"

namespace bodyrec::cli {

void add_orient_options(CLI::App& sub, OrientCliOptions& options) {
  OrientPipelineOptions& o = options.pipeline;
  add_enum_option(sub, "--views", o.orientation.method,
                  std::vector<std::pair<std::string, ViewMethod>>{{"robust", ViewMethod::kRobust},
                                                                  {"thesis", ViewMethod::kThesis}},
                  "robust (skeleton or depth axis, faces, motion, continuity) or thesis (Ch6 interval table)",
                  "robust");
  sub.add_flag_function(
      "--no-faces", [&o](int64_t) { o.orientation.use_faces = false; },
      "Do not run the face detector (thesis: the face flag is then unknown)");
  sub.add_flag("--depth-only", o.bodies.depth_only, "Ignore skeletons: orient from the body pixels' depth (robust only)");
  std::vector<std::pair<std::string, BodySource>> sources;
  for (BodySource s : {BodySource::kAuto, BodySource::kSkeleton, BodySource::kBodyIndex, BodySource::kDepth})
    sources.emplace_back(to_string(s), s);
  add_enum_option(sub, "--bodies-from", o.bodies.from, sources,
                  "auto: skeletons, else body index, else own depth segmentation; or force skeleton, body-index "
                  "(slots only) or depth (segment the depth image, ignore the sensor's bodies)",
                  "auto");
  sub.add_option("--max-frames", options.max_frames, "Stop after this many frames; -1 = all");
  add_segment_options(sub, options.seg);
}

bool is_skeleton_file(const std::string& input) {
  return input.size() > 9 && input.compare(input.size() - 9, 9, ".skeleton") == 0;
}

OrientSource::OrientSource(const std::string& input) : name_(input) {
  if (is_skeleton_file(input)) {
    const NtuSkeleton s = read_ntu_skeleton(input);
    double rms[2];
    meta_.sensor = "Kinect v2 (NTU RGB+D skeleton)";
    meta_.streams.bodies = true;
    fit_ntu_cameras(s, meta_, rms);
    ntu_ = ntu_bodies(s, input);
    frames_ = static_cast<int>(ntu_.size());
  } else {
    reader_.emplace(input);
    meta_ = reader_->meta();
    frames_ = reader_->frame_count();
  }
}

bool OrientSource::read(RgbdFrame& f) {
  if (reader_) return reader_->read(f);
  if (next_ >= frames_) return false;
  f = RgbdFrame{};
  f.index = next_;
  f.time_s = next_ / meta_.fps;
  f.bodies = std::move(ntu_[static_cast<size_t>(next_)]);
  ++next_;
  return true;
}

std::optional<DepthSegmenter> OrientSource::segmenter(const OrientCliOptions& options) const {
  if (!reader_ || !uses_own_segmentation(meta_, options.pipeline.bodies)) return std::nullopt;
  return make_segmenter(*reader_, options.seg);
}

void check_orient_options(const OrientCliOptions& options) {
  if (options.pipeline.bodies.depth_only && options.pipeline.orientation.method == ViewMethod::kThesis)
    throw UsageError("--depth-only needs --views robust (the thesis rule reads joint quaternions)");
}

int run_orientation(const std::string& input, const OrientCliOptions& options,
                    const std::function<void(const OrientFrame&)>& sink) {
  check_orient_options(options);
  OrientSource source(input);
  OrientPipeline pipeline(source.meta(), options.pipeline, source.segmenter(options), input);
  const int frames = options.max_frames >= 0 ? std::min(source.frame_count(), options.max_frames) : source.frame_count();
  int done = 0;
  for (RgbdFrame f; done < frames && source.read(f); ++done) {
    const OrientResult result = pipeline.process(f);
    sink({f, result});
  }
  return done;
}

}  // namespace bodyrec::cli
