// Shared by `bodyrec reid` and `bodyrec eval reid-stream`: the options of online re-identification, and the
// loop that reads frames one by one through a ReidPipeline (reid/reid_pipeline.h: a recording or a live
// sensor) or a ColourReidPipeline (reid/colour_reid_pipeline.h: a video, images, a camera, or a recording's
// colour alone) on a store.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bodyrec/core/percentile.h"
#include "bodyrec/reid/gallery_reid_store.h"
#include "bodyrec/reid/reid_pipeline.h"
#include "colour_input.h"
#include "frame_loop.h"
#include "gallery_options.h"
#include "orient_job.h"

namespace bodyrec::cli {

// --match-views: which of a user's views a scan is compared with.
enum class MatchViews { kAll, kNear };

struct ReidCliOptions {
  OrientCliOptions orient;
  GalleryCliOptions gallery;
  std::string matcher = "stripes", model;
  bool no_images = false;
  std::optional<MatchViews> match_views;  // none: near for the thesis's kaze matcher, else all
  std::string prune_unseen_for;  // retention, applied before the run; "" = keep everyone
  int max_events_per_user = GalleryOptions{}.max_events_per_user;  // event history cap; 0 = all
  std::string sensor;  // recorded with the gallery's events (reid --sensor-id)
  OnlineReidOptions reid;
  int stature_wait = -1;  // --stature-wait; -1: ReidPipelineOptions' default
  ColourCliOptions colour;  // the plain-camera path (orient.live: a sensor, --realtime)
};

// --gallery, --matcher, --model, --no-images, --prune-unseen-for, --max-events-per-user, --decide-after, --max-wait,
// --min-quality, --threshold, --left-after, the orientation/segmentation options and the plain-camera options
// (colour_input.h; --camera with `camera`).
void add_reid_options(CLI::App& sub, ReidCliOptions& options, bool gallery_option = true, bool camera = false);

// The --match-views in effect: as given, else near for the kaze matcher (the thesis compares a scan with the
// same and the complementary view) and all for the others.
MatchViews match_views(const ReidCliOptions& options);
const char* to_string(MatchViews views);

struct ReidFrame {
  const RgbdFrame& frame;  // index -1: the line after the last frame, with finish()'s events
  const std::vector<OrientedBody>& bodies;  // same order as step.identities
  const ReidStep& step;
  double ms_orient = 0, ms_scan = 0, ms_reid = 0;  // colour: ms_orient is detection and tracking
  const FrameArrival* arrival = nullptr;  // when the frame came (live runs: for the output's times)
  bool colour = false;                    // from the colour pipeline
  bool live = false;                      // a sensor, a camera or --realtime
  int truth_visible = -1;                 // colour-only with truth scoring: people visible in the frame
};

// What a run needs before any file is written: the recording (InputError when it cannot be read or lacks
// colour or depth) and the matcher (UsageError/InputError for a bad name or model). Open it before creating a
// gallery or output, so a wrong path leaves no empty files behind.
struct ReidInput {
  std::string path;
  std::unique_ptr<OrientSource> source;  // RGB-D frames: a recording (also for --colour-only) or a sensor
  std::unique_ptr<AppearanceMatcher> matcher;
  std::unique_ptr<ColourInput> colour;   // the plain-camera path
  bool score_truth = false;  // colour-only on a recording with truth: each body's true person (evaluation)
  // Colour-only diagnosis: bodies from the truth (colour_truth.h) instead of the detector and tracker, with
  // their true masks or (kBoxes) the foreground inside their boxes; or (kDetections) the true boxes as the
  // tracker's detections (the foreground cuts them out).
  enum class TrueBodies { kNone, kMasks, kBoxes, kDetections } true_bodies = TrueBodies::kNone;
};
ReidInput open_reid_input(const std::string& input, const ReidCliOptions& options);

// The start of the clock that the run's gallery times follow (GalleryReidStoreOptions::start): a
// recording's or a video file's own (source_clock.h), none (the wall clock) for a live source, a camera and
// an image folder.
std::optional<GalleryTime> gallery_clock_start(const ReidInput& in, const ReidCliOptions& options);

struct ReidRunStats {
  int frames = 0;
  long dropped = 0;                  // live: frames dropped because processing fell behind
  bool stopped = false;              // ended by SIGINT/SIGTERM
  std::vector<double> latency_ms;    // per event: from its frame's arrival to the return of `sink`
};

// Runs the frames through on `store` (live sources through the grabber, until their end, --max-frames or a
// signal); `sink` gets every frame and, with frame.index = -1, finish()'s `left` events. Errors as the
// readers and the store say; output already passed to `sink` stays valid.
ReidRunStats run_reid(ReidInput& input, const ReidCliOptions& options, ReidStore& store,
                      const std::function<void(const ReidFrame&)>& sink);


// Opens (or creates) the gallery the options name; one that holds scans and no image is kept features only.
std::unique_ptr<Gallery> open_reid_gallery(const ReidCliOptions& options, const std::string& path);

}  // namespace bodyrec::cli
