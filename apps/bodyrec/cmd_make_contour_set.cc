// `bodyrec make-contour-set`: body-contour landmark training data (imglab XML) from Penn-Fudan masks.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "bodyrec/io/json_numbers.h"
#include "bodyrec/landmarks/contour_set.h"
#include "command.h"

namespace bodyrec::cli {
namespace {

struct MakeContourSetCommand {
  ContourSetOptions options;
  bool json = false;

  void run() const {
    const ContourSetReport r = build_pennfudan_contour_set(options);
    auto skipped = [&](ContourStatus s) {
      const auto it = r.skipped.find(s);
      return it == r.skipped.end() ? 0 : it->second;
    };
    std::printf("images        train %d, test %d (sorted names, index %% 4 == 3 is test)\n", r.train_images,
                r.test_images);
    std::printf("people        train %d, test %d with %d landmarks", r.train_people, r.test_people,
                options.contour.landmarks);
    if (options.flip) std::printf(" (+%d mirrored in train)", r.flipped_people);
    std::printf("\n");
    std::printf("skipped       %d: %d touching the border (> %.0f %% of the outline), %d under %d px tall, "
                "%d empty masks (kept as ignore boxes)\n",
                r.skipped_total(), skipped(ContourStatus::kTouchesBorder), 100 * options.contour.max_border_fraction,
                skipped(ContourStatus::kTooSmall), options.contour.min_height, skipped(ContourStatus::kEmpty));
    std::printf("wrote         %s/train.xml, %s/test.xml, %s/images/\n", options.out_dir.c_str(),
                options.out_dir.c_str(), options.out_dir.c_str());
    if (json) {
      const nlohmann::json j = {{"train_images", r.train_images},
                                {"test_images", r.test_images},
                                {"train_people", r.train_people},
                                {"test_people", r.test_people},
                                {"flipped_people", r.flipped_people},
                                {"skipped_border", skipped(ContourStatus::kTouchesBorder)},
                                {"skipped_small", skipped(ContourStatus::kTooSmall)},
                                {"skipped_empty", skipped(ContourStatus::kEmpty)}};
      std::printf("%s\n", json_text(j).c_str());
    }
  }
};

void add(CLI::App& app) {
  auto command = std::make_shared<MakeContourSetCommand>();
  CLI::App* sub = app.add_subcommand(
      "make-contour-set", "Make body-contour landmark training data (imglab XML) from Penn-Fudan instance masks");
  sub->footer(
      "Per person: outline of its mask, N points equally spaced by arc length, point 0 at the top of the head,\n"
      "clockwise in the image. Writes OUT/train.xml, OUT/test.xml and OUT/images/.\n"
      "Example: bodyrec make-contour-set --pennfudan ../shared/datasets/pennfudan --landmarks 180 --out out/contours "
      "--flip");
  auto& o = command->options;
  sub->add_option("--pennfudan", o.pennfudan_dir, "Penn-Fudan folder (PNGImages/, PedMasks/, Annotation/)")
      ->required();
  sub->add_option("--out", o.out_dir, "Output folder")->required();
  sub->add_option("--landmarks", o.contour.landmarks, "Landmarks per person")->capture_default_str();
  sub->add_option("--box-margin", o.box_margin,
                  "Grow each annotation box by this fraction of its width/height on every side")
      ->capture_default_str();
  sub->add_flag("--flip", o.flip, "Add mirrored copies of the training images (landmark order kept clockwise)");
  sub->add_option("--min-height", o.contour.min_height, "Skip people shorter than this (pixels)")
      ->capture_default_str();
  sub->add_option("--max-border", o.contour.max_border_fraction,
                  "Skip people with more than this fraction of their outline on the image border")
      ->capture_default_str();
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (train/test images and people, skipped per reason)");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"", 30, add});

}  // namespace
}  // namespace bodyrec::cli
