#include "reid_job.h"

#include <map>

#include "bodyrec/core/error.h"
#include "enum_option.h"
#include "option_checks.h"
#include "source_clock.h"

namespace bodyrec::cli {

void add_reid_options(CLI::App& sub, ReidCliOptions& o, bool gallery_option, bool camera) {
  if (gallery_option) add_gallery_path_option(sub, o.gallery);
  std::string names;
  for (const auto& n : matcher_names()) names += (names.empty() ? "" : ", ") + n;
  sub.add_option("--matcher", o.matcher,
                 "Appearance matcher: " + names +
                     ". stripes (default): colour histograms in bands of height above the floor, no model needed; "
                     "default: LOMO/GOG + XQDA with the shipped model (models/README.md) or --model; default-full: the "
                     "same on the unsketched features, needs --model (bodyrec train-reid --matcher default-full); "
                     "lomo-xqda: the published LOMO + XQDA, needs --model (bodyrec train-reid); kaze: the thesis's "
                     "score")
      ->capture_default_str();
  sub.add_option("--model", o.model,
                 "Learned model for --matcher default (instead of the shipped one), default-full or lomo-xqda (bodyrec "
                 "train-reid --out)");
  sub.add_flag("--no-images", o.no_images, "Store features only: no body pixels in the gallery. A gallery that holds scans and no image "
                                   "stays so: later runs store no images in it either");
  sub.add_option("--prune-unseen-for", o.prune_unseen_for,
                 "Before the run, forget users unseen for this long (30d, 12h, 45m...)");
  sub.add_option("--max-events-per-user", o.max_events_per_user,
                 "The gallery keeps the newest this many events per user (enrolled, recognised, view added, left); "
                 "older ones are erased, so the file stays bounded however often people come back. 0 = keep all")
      ->check(non_negative())
      ->capture_default_str();
  sub.add_option("--decide-after", o.reid.decide_after,
                 "Scans a new body collects before it is recognised or enrolled (a sure recognition, both of its "
                 "first 2 scans clearly for one user of the same stature, comes sooner)")
      ->capture_default_str();
  sub.add_option("--max-wait", o.reid.max_wait_frames, "Frames after which a body is decided with the scans it has")
      ->capture_default_str();
  sub.add_option("--stature-wait", o.stature_wait,
                 "Frames a body whose stature is not measured yet (head hidden) waits before it is recognised as a "
                 "user whose stature is known, so that people who dress alike are not taken for each other (the "
                 "--max-wait decision comes first when sooner). Default: 30, and 0 when the bodies come from "
                 "bodyrec's own depth segmentation, whose statures are often refused (people side by side)")
      ->check(non_negative())
      ->default_str("30, depth: 0");
  sub.add_option("--min-quality", o.reid.min_quality, "Partial scans below this quality (0..1) are not used")
      ->capture_default_str();
  sub.add_option("--threshold", o.reid.threshold,
                 "Similarity above which a scan matches a user (default: the matcher's own threshold)")
      ->default_str("matcher's");
  sub.add_option("--margin", o.reid.margin,
                 "A scan votes for its best user only when it beats the next by this share of |threshold|")
      ->capture_default_str();
  sub.add_option("--new-gap", o.reid.new_gap,
                 "A scan says \"new person\" only when its best user is below the threshold by this share of "
                 "|threshold|")
      ->capture_default_str();
  add_enum_option(sub, "--match-views", o.match_views,
                  std::vector<std::pair<std::string, MatchViews>>{{"all", MatchViews::kAll}, {"near", MatchViews::kNear}},
                  "all: compare a scan with every view of a user; near: same and complementary views only (thesis), "
                  "all views when the user has none of those",
                  "near with --matcher kaze (the thesis), else all");
  sub.add_option("--stature-weight", o.reid.stature_weight,
                 "Stature fused with appearance: a user whose stature (top of the depth points above the floor) "
                 "differs from the body's by more than 4 cm loses this share of |threshold| per further cm; 0 = "
                 "appearance only")
      ->capture_default_str();
  sub.add_option("--left-after", o.reid.left_after_s, "Seconds unseen after which a body has left")
      ->capture_default_str();
  add_orient_options(sub, o.orient);
  add_colour_options(sub, o.colour, camera);
}

MatchViews match_views(const ReidCliOptions& options) {
  if (options.match_views) return *options.match_views;
  return options.matcher == "kaze" ? MatchViews::kNear : MatchViews::kAll;
}

const char* to_string(MatchViews views) { return views == MatchViews::kNear ? "near" : "all"; }

std::unique_ptr<Gallery> open_reid_gallery(const ReidCliOptions& options, const std::string& path) {
  GalleryOptions g;
  g.create = true;
  g.store_images = !options.no_images;
  g.max_events_per_user = options.max_events_per_user;
  g.sensor = options.sensor;
  auto gallery = std::make_unique<Gallery>(path, g);
  // A gallery kept with --no-images stays features only: a run that leaves the flag out stores no pixels in it.
  if (g.store_images && gallery->scan_count() > 0 && gallery->scans_with_images() == 0) gallery->keep_features_only();
  if (!options.prune_unseen_for.empty())
    gallery->prune_unseen(parse_retention(options.prune_unseen_for, "--prune-unseen-for"));
  return gallery;
}

ReidInput open_reid_input(const std::string& input, const ReidCliOptions& options) {
  check_orient_options(options.orient);
  const LiveCliOptions& live = options.orient.live;
  if (!live.sensor && is_colour_input(input, options.colour)) {
    ReidInput in{input, nullptr, nullptr, nullptr};
    if (options.colour.colour_only && options.colour.camera >= 0)
      throw UsageError("--colour-only reads a recording's colour; --camera is colour already");
    if (options.colour.colour_only) {
      if (is_skeleton_file(input)) throw InputError(input + ": --colour-only needs a recording with colour");
      in.source = std::make_unique<OrientSource>(input, live);
      if (!in.source->meta().streams.color) throw InputError(input + "/meta.json: --colour-only needs a colour stream");
    }
    in.colour = open_colour_input(input, options.colour, options.orient.pipeline.orientation.use_faces, options.reid);
    if (live.realtime && in.colour->frames && !in.colour->video)
      throw UsageError("--realtime plays a recording or a video at its frame rate; " + in.colour->frames->describe() +
                       " has none");
    in.matcher = make_matcher(options.matcher, options.model);
    return in;
  }
  if (options.colour.colour_only) throw UsageError("--colour-only reads a recording, not a sensor");
  refuse_plain_camera_options(options.colour, live.sensor ? "the sensor" : input);
  if (!live.sensor && is_skeleton_file(input))
    throw InputError(input + ": re-identification needs a recording with colour and depth");
  ReidInput in{input, std::make_unique<OrientSource>(input, live), nullptr, nullptr};
  if (!in.source->meta().streams.color || !in.source->meta().streams.depth)
    throw InputError(in.source->name() + (live.sensor ? "" : "/meta.json") +
                     ": re-identification needs colour and depth streams");
  in.matcher = make_matcher(options.matcher, options.model);
  return in;
}

std::optional<GalleryTime> gallery_clock_start(const ReidInput& in, const ReidCliOptions& options) {
  if (options.orient.live.live() || options.colour.camera >= 0) return std::nullopt;
  const GalleryTime now = GalleryClock::now();
  if (in.colour && in.colour->frames) {
    const auto fps = in.colour->frames->fps();
    const auto count = in.colour->frames->frame_count();
    if (!in.colour->video || !fps || !count || *fps <= 0) return std::nullopt;
    return file_source_start(in.path, *count / *fps, now);
  }
  if (!in.source) return std::nullopt;
  const RecordingMeta& meta = in.source->meta();
  return file_source_start(in.path + "/meta.json", meta.fps > 0 ? meta.frame_count / meta.fps : 0, now);
}

}  // namespace bodyrec::cli
