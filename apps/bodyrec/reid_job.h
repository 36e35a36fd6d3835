// Shared by `bodyrec reid` and `bodyrec eval reid-stream`: reads a recording, finds and orients its
// bodies (orient_job.h: skeletons, body index only, or own depth segmentation), takes partial scans of
// the bodies the online re-identification wants, and runs OnlineReid frame by frame on a gallery.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bodyrec/reid/online_reid.h"
#include "gallery_options.h"
#include "orient_job.h"

namespace bodyrec::cli {

struct ReidCliOptions {
  OrientCliOptions orient;
  GalleryCliOptions gallery;
  std::string matcher = "stripes", model;
  bool no_images = false;
  std::string match_views;  // "all" or "near"; empty: near for the thesis's kaze matcher, else all
  std::string prune_unseen_for;  // retention, applied before the run; "" = keep everyone
  int max_events_per_user = GalleryOptions{}.max_events_per_user;  // event history cap; 0 = all
  std::string sensor;  // recorded with the gallery's events (reid --sensor-id)
  OnlineReidOptions reid;
  int stature_wait = -1;  // --stature-wait; -1: reid's default, 0 when the bodies come from our own depth segmentation
};

// --gallery, --matcher, --model, --no-images, --prune-unseen-for, --max-events-per-user, --decide-after, --max-wait,
// --min-quality, --threshold, --left-after and the orientation/segmentation options.
void add_reid_options(CLI::App& sub, ReidCliOptions& options, bool gallery_option = true);

struct ReidFrame {
  const RgbdFrame& frame;
  std::vector<OrientedBody> bodies;  // same order as step.identities
  ReidStep step;
  double ms_orient = 0, ms_scan = 0, ms_reid = 0;
};

// What a run needs before any file is written: the recording's meta (InputError when it cannot be read
// or lacks colour or depth) and the matcher (UsageError/InputError for a bad name or model). Open it
// before creating a gallery or output, so a wrong path leaves no empty files behind.
struct ReidInput {
  std::string path;
  RecordingMeta meta;
  std::unique_ptr<AppearanceMatcher> matcher;
};
ReidInput open_reid_input(const std::string& input, const ReidCliOptions& options);

// Runs the recording through; `sink` gets every frame (and, with an empty frame.index = -1 frame, the
// final `left` events of finish()). Returns the number of frames. Errors as the readers and the
// gallery say; output already passed to `sink` stays valid.
int run_reid(const ReidInput& input, const ReidCliOptions& options, Gallery& gallery,
             const std::function<void(const ReidFrame&)>& sink);

// The --match-views in effect: as given, else "near" for the kaze matcher (the thesis compares a scan with
// the same and the complementary view) and "all" for the others.
std::string match_views(const ReidCliOptions& options);

// Opens (or creates) the gallery the options name.
std::unique_ptr<Gallery> open_reid_gallery(const ReidCliOptions& options, const std::string& path);

}  // namespace bodyrec::cli
