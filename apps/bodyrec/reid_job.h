// Shared by `bodyrec reid` and `bodyrec eval reid-stream`: the options of online re-identification, and the
// loop that reads a recording frame by frame through a ReidPipeline (reid/reid_pipeline.h) on a store.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bodyrec/reid/gallery_reid_store.h"
#include "bodyrec/reid/reid_pipeline.h"
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
  OnlineReidOptions reid;
  int stature_wait = -1;  // --stature-wait; -1: ReidPipelineOptions' default
};

// --gallery, --matcher, --model, --no-images, --prune-unseen-for, --max-events-per-user, --decide-after, --max-wait,
// --min-quality, --threshold, --left-after and the orientation/segmentation options.
void add_reid_options(CLI::App& sub, ReidCliOptions& options, bool gallery_option = true);

// The --match-views in effect: as given, else near for the kaze matcher (the thesis compares a scan with the
// same and the complementary view) and all for the others.
MatchViews match_views(const ReidCliOptions& options);
const char* to_string(MatchViews views);

struct ReidFrame {
  const RgbdFrame& frame;  // index -1: the line after the last frame, with finish()'s events
  const std::vector<OrientedBody>& bodies;  // same order as step.identities
  const ReidStep& step;
  double ms_orient = 0, ms_scan = 0, ms_reid = 0;
};

// What a run needs before any file is written: the recording (InputError when it cannot be read or lacks
// colour or depth) and the matcher (UsageError/InputError for a bad name or model). Open it before creating a
// gallery or output, so a wrong path leaves no empty files behind.
struct ReidInput {
  std::string path;
  std::unique_ptr<OrientSource> source;
  std::unique_ptr<AppearanceMatcher> matcher;
};
ReidInput open_reid_input(const std::string& input, const ReidCliOptions& options);

// Runs the recording through on `store`; `sink` gets every frame and, with frame.index = -1, finish()'s
// `left` events. Returns the number of frames. Errors as the readers and the store say; output already passed
// to `sink` stays valid.
int run_reid(ReidInput& input, const ReidCliOptions& options, ReidStore& store,
             const std::function<void(const ReidFrame&)>& sink);

// Opens (or creates) the gallery the options name.
std::unique_ptr<Gallery> open_reid_gallery(const ReidCliOptions& options, const std::string& path);

}  // namespace bodyrec::cli
