// `bodyrec eval reid-stream REC`: runs online re-identification over a recording with truth (bodyrec
// synth), or over a video or image sequence with a ground-truth file of boxes and ids (--gt), on a fresh
// store in memory (or --gallery) and scores it: per-frame identity accuracy, splits, merges
// (eval/reid_stream_metrics.h), ms per frame.
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>

#include "bodyrec/core/error.h"
#include "bodyrec/eval/reid_stream_metrics.h"
#include "bodyrec/io/ground_truth.h"
#include "bodyrec/io/json_numbers.h"
#include "bodyrec/io/sinks.h"
#include "bodyrec/reid/colour_truth.h"
#include "bodyrec/reid/memory_reid_store.h"
#include "bodyrec/reid/visit_separability.h"
#include "command.h"
#include "option_checks.h"
#include "enum_option.h"
#include "reid_output.h"

namespace bodyrec::cli {
namespace {

struct EvalReidStreamCommand {
  std::string input, jsonl, gallery, gt;
  double gt_iou = 0.5;
  ReidCliOptions options;
  bool json = false;
  ReidInput::TrueBodies true_bodies = ReidInput::TrueBodies::kNone;

  void run() const {
    ReidInput in = open_reid_input(input, options);  // before any file is created
    if (!gt.empty() && in.source) throw UsageError("--gt is for a video or images: a recording has its own truth");
    if (!in.source && gt.empty())
      throw InputError(input + ": eval reid-stream needs a recording with truth (bodyrec synth; --colour-only for its "
                               "colour alone) or, for a video or images, --gt with their people's boxes and ids");
    if (true_bodies != ReidInput::TrueBodies::kNone && !in.source)
      throw UsageError("--true-bodies is for --colour-only on a recording");
    if (true_bodies != ReidInput::TrueBodies::kNone && !in.colour) throw UsageError("--true-bodies is for --colour-only");
    // A ground-truth file: each body is the person whose box it overlaps (IoU >= --gt-iou, one to one).
    std::map<int, std::vector<LabelledBox>> truth_by_frame;
    int truth_frames = 0;
    if (!gt.empty()) {
      GroundTruth truth = read_ground_truth(gt);
      truth_frames = truth.frame_count;
      std::vector<LabelledBox>& rows = truth.boxes;
      rows.erase(std::remove_if(rows.begin(), rows.end(), [](const LabelledBox& b) { return b.ignore || b.id < 0; }),
                 rows.end());
      truth_by_frame = truth.by_frame();
      if (truth_by_frame.empty())
        throw InputError(gt + ": every row is ignored (zero confidence, another class or no id): no person to score");
    }
    std::unique_ptr<JsonlWriter> lines;
    if (!jsonl.empty()) lines = std::make_unique<JsonlWriter>(jsonl);
    // A fresh store in memory unless a gallery is named.
    std::unique_ptr<Gallery> g;
    std::unique_ptr<ReidStore> store;
    if (gallery.empty()) {
      store = std::make_unique<MemoryReidStore>();
    } else {
      g = open_reid_gallery(options, gallery);
      store = std::make_unique<GalleryReidStore>(*g, *in.matcher, GalleryReidStoreOptions{input, std::nullopt});
    }
    in.score_truth = true;
    in.true_bodies = true_bodies;
    ReidStreamCounter counter;
    // With true bodies: how far apart the matcher's descriptors of clear true-mask scans put people
    // across their visits.
    std::unique_ptr<VisitSeparability> separability;
    if (true_bodies != ReidInput::TrueBodies::kNone) separability = std::make_unique<VisitSeparability>(*in.matcher);
    bool any_truth = false;
    int last_frame = -1, visible = 0;
    double ms = 0, last_time = 0;
    const int frames = run_reid(in, options, *store, [&](const ReidFrame& f) {
      if (f.truth_visible > 0) visible += f.truth_visible;
      // With --gt: each body's person by its box (-1 none), scored and written to --jsonl.
      std::vector<int> gt_person(f.bodies.size(), -1);
      if (!gt.empty() && f.frame.index >= 0 && f.frame.index < truth_frames) {
        const auto it = truth_by_frame.find(f.frame.index);
        any_truth |= it != truth_by_frame.end();
        std::vector<Box> bodies, people;
        if (it != truth_by_frame.end())
          for (const LabelledBox& p : it->second) people.push_back(p.box);
        visible += static_cast<int>(people.size());
        for (const ReidIdentity& id : f.step.identities) bodies.push_back(Box(id.box));
        const std::vector<int> match = match_bodies_to_truth(bodies, people, gt_iou);
        for (size_t i = 0; i < match.size(); ++i) {
          if (match[i] < 0) continue;
          gt_person[i] = it->second[static_cast<size_t>(match[i])].id;
          counter.add(gt_person[i], f.bodies[i].key, f.step.identities[i].user);
        }
      }
      if (f.frame.index >= 0) {
        last_frame = f.frame.index;
        last_time = f.frame.time_s;
        ms += f.ms_orient + f.ms_scan + f.ms_reid;
      }
      if (lines) {
        // The run's line, plus each body's true person (identity; null when it matches nobody).
        nlohmann::json j = reid_frame_json(f, last_frame + 1, last_time);
        for (size_t i = 0; i < f.bodies.size(); ++i) {
          const int t = f.bodies[i].truth;
          j["bodies"][i]["person"] =
              !gt.empty() ? (gt_person[i] >= 0 ? nlohmann::json(gt_person[i]) : nlohmann::json())
              : f.frame.truth && t >= 0 ? nlohmann::json(f.frame.truth->people[static_cast<size_t>(t)].identity)
                                        : nlohmann::json();
        }
        lines->write(j);
      }
      if (separability && f.frame.truth && f.frame.index >= 0)
        for (const TrueBody& t : bodyrec::true_bodies(in.source->meta(), f.frame)) {
          const auto scan = colour_scan(f.frame.color, t.box, t.mask, ViewEstimate{}, 0.0);
          if (scan && scan->quality >= TrackSegmentOptions{}.min_quality)
            separability->add(f.frame.truth->people[static_cast<size_t>(t.person)].identity, t.track,
                              in.matcher->describe(PersonImage{scan->image, scan->mask, scan->row_height_m}));
        }
      if (f.frame.truth) {
        any_truth = true;
        for (size_t i = 0; i < f.bodies.size(); ++i) {
          const OrientedBody& b = f.bodies[i];
          if (b.truth >= 0)
            counter.add(f.frame.truth->people[static_cast<size_t>(b.truth)].identity, b.key, f.step.identities[i].user);
        }
      }
      for (const ReidEvent& e : f.step.events)
        if (e.kind == ReidEventKind::kEnrolled || e.kind == ReidEventKind::kRecognised) counter.assign(e.track, e.user);
    }).frames;
    if (!any_truth)
      throw InputError(gt.empty() ? input + ": the recording has no truth stream (make one with bodyrec synth)"
                                  : gt + ": no ground truth for the frames of " + input);
    const ReidStreamScore s = counter.score();
    if (!gt.empty() && s.frames == 0)
      throw InputError(gt + ": no tracked body of " + input + " overlaps a ground-truth box at IoU >= " +
                       std::to_string(gt_iou) + " (other frame numbering or image size?)");
    const double per_frame = frames ? ms / frames : 0.0;
    std::printf("frames        %d (%d body-frames with a true person)\n", frames, s.frames);
    std::printf("accuracy      %.4f (right user / body-frames; %d still undecided count wrong)\n", s.accuracy,
                s.undecided);
    std::printf("people        %d true identities, %d users, %d tracks\n", s.identities, s.users, s.tracks);
    std::printf("splits        %d (one person enrolled as more than one user)\n", s.splits);
    std::printf("merges        %d (two people given one user)\n", s.merges);
    std::printf("ms per frame  %.2f (%s matcher)\n", per_frame, options.matcher.c_str());
    // Colour-only: the people the detector and tracker never gave a body are not in the body-frames above.
    const double coverage = visible > 0 ? static_cast<double>(s.frames) / visible : 0.0;
    if (in.colour) std::printf("coverage      %.4f (body-frames with a true person / people visible)\n", coverage);
    VisitSeparability::Score sep;
    if (separability) {
      sep = separability->score();
      std::printf("separability  %.4f nearest other-visit scan is the same person, %.4f above the threshold (%d clear "
                  "true-mask scans of people seen twice)\n",
                  sep.nn_accuracy, sep.above_threshold, sep.probes);
    }
    if (json) {
      nlohmann::json j({{"accuracy", s.accuracy},
                        {"splits", s.splits},
                        {"merges", s.merges},
                        {"frames", frames},
                        {"body_frames", s.frames},
                        {"undecided", s.undecided},
                        {"users", s.users},
                        {"identities", s.identities},
                        {"ms_per_frame", per_frame},
                        {"colour_only", in.colour != nullptr},
                        {"coverage", in.colour ? nlohmann::json(coverage) : nlohmann::json()},
                        {"matcher", options.matcher},
                        {"match_views", to_string(match_views(options))}});
      if (separability)
        j["separability"] = {{"nn_accuracy", sep.nn_accuracy}, {"above_threshold", sep.above_threshold}, {"probes", sep.probes}};
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<EvalReidStreamCommand>();
  CLI::App* sub = app.add_subcommand(
      "reid-stream",
      "Score online re-identification on a recording with truth, or footage with --gt: per-frame accuracy, splits, merges");
  sub->add_option("REC", command->input,
                  "Recording with a truth stream (bodyrec synth); with --colour-only its colour frames alone, each "
                  "tracked box scored as the true person whose pixels fill most of it. Or a video or images with --gt")
      ->required();
  sub->add_option("--gt", command->gt,
                  "For a video or images: ground-truth boxes with person ids, PETS/CVML XML (.xml) or MOTChallenge "
                  "gt.txt; each tracked box is scored as the person whose box it overlaps most (IoU >= --gt-iou, one "
                  "to one). The file's ids are the people: one who comes back under a new id counts as another person");
  sub->add_option("--gt-iou", command->gt_iou, "Least IoU between a body's box and its person's box with --gt")
      ->check(in_range(0.05, 1.0))
      ->capture_default_str();
  sub->add_option("--gallery", command->gallery,
                  "Start from (and write to) this gallery instead of a fresh one in memory");
  add_reid_options(*sub, command->options, false);
  sub->add_option("--jsonl", command->jsonl, "The run's per-frame output, as `bodyrec reid --jsonl` writes it, each body with its true \"person\" (identity, null when none)");
  add_enum_option(*sub, "--true-bodies", command->true_bodies,
                  std::vector<std::pair<std::string, ReidInput::TrueBodies>>{{"none", ReidInput::TrueBodies::kNone},
                                                                             {"masks", ReidInput::TrueBodies::kMasks},
                                                                             {"boxes", ReidInput::TrueBodies::kBoxes},
                                                                             {"detections", ReidInput::TrueBodies::kDetections}},
                  "With --colour-only, a diagnosis of what detection and tracking lose: the bodies and their track "
                  "ids from the recording's truth instead of the detector and tracker, cut out by their true masks "
                  "(masks) or by the foreground inside their boxes (boxes); detections: the true boxes as the "
                  "tracker's detections (the tracker's ids, foreground masks); none: detected and tracked",
                  "none");
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (accuracy, splits, merges, frames, body_frames, undecided, users, "
                "identities, ms_per_frame, colour_only, coverage: colour-only body-frames with a true person over "
                "the people visible; with --true-bodies, separability: nn_accuracy, above_threshold, probes)");
  sub->footer("Example: bodyrec synth --scenario reenter --people 5 --frames 300 --seed 2 --out rec -q && "
              "bodyrec eval reid-stream rec --json && bodyrec eval reid-stream rec --colour-only --json\n"
              "A video with ground truth: bodyrec eval reid-stream vtest.avi --gt PETS2009-S2L1.xml --json");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"eval", 64, add});

}  // namespace
}  // namespace bodyrec::cli
