// `bodyrec eval landmarks`: landmark error of a shape model inside the ground-truth boxes of an imglab set.
#include <cstdio>

#include "bodyrec/core/error.h"
#include "bodyrec/io/sinks.h"
#include "bodyrec/landmarks/body_shape.h"
#include "bodyrec/landmarks/landmark_dataset.h"
#include "bodyrec/landmarks/landmark_metrics.h"
#include "command.h"
#include "landmark_report.h"
#include "shape_fitting_options.h"

namespace bodyrec::cli {
namespace {

struct EvalLandmarksCommand {
  std::string xml, shape, per_person;
  ShapeFittingOptions fitting;
  bool json = false;

  void run() const {
    BodyShapeModel model(shape_model_path(shape));
    fitting.apply(model);
    const LandmarkDataset data = load_landmark_dataset(xml);
    if (data.landmarks == 0) throw InputError(xml + ": no box has landmarks (<part> elements)");
    std::vector<PersonLandmarkError> errors;
    const LandmarkScores s = evaluate_body_shape(model, data, xml, &errors);
    if (!per_person.empty()) {
      JsonlWriter out(per_person);
      for (size_t i = 0; i < errors.size(); ++i) {
        const auto& e = errors[i];
        out.write({{"person", i},
                   {"image", data.images[e.image].path},
                   {"mean_px", e.mean_px},
                   {"rel_height", e.mean_px / e.box_height},
                   {"rel_width", e.mean_px / e.image_width},
                   {"contour_px", e.contour_px},
                   {"box_height", e.box_height}});
      }
    }
    print_landmark_scores(xml, s);
    if (json) std::printf("%s\n", landmark_scores_json(s).dump().c_str());
  }
};

void add(CLI::App& eval) {
  auto command = std::make_shared<EvalLandmarksCommand>();
  CLI::App* sub = eval.add_subcommand("landmarks", "Score a body shape model inside ground-truth boxes");
  sub->footer(
      "Error per person = mean distance between predicted and true landmark i; also divided by the box height\n"
      "and by the image width (the thesis's measure), and point-to-contour (distance to the true outline).\n"
      "The model's shape correction stays on with --mask-threshold, --threshold-offsets, --no-mirror and\n"
      "--no-leg-slit: it was learnt on fits with the defaults but still lowers the error with each\n"
      "(docs/benchmarks.md).\n"
      "Example: bodyrec eval landmarks out/contours/test.xml --shape out/shape.dat --json");
  sub->add_option("test", command->xml, "imglab XML with numbered <part>s per box")->required();
  add_shape_model_option(*sub, command->shape);
  add_shape_fitting_options(*sub, command->fitting);
  sub->add_option("--per-person", command->per_person,
                  "Write every person's error as JSON lines (person, image, mean_px, rel_height, rel_width, "
                  "contour_px); `bodyrec report --eval FILE` draws their histogram");
  sub->add_flag("--json", command->json,
                "End stdout with one JSON object (mean_px, mean_rel_height, mean_rel_width, p90_rel_height, "
                "persons, ms_per_person, ...)");
  sub->callback([command] { command->run(); });
}

const bool registered = register_command({"eval", 30, add});

}  // namespace
}  // namespace bodyrec::cli
