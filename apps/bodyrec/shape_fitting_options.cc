#include "shape_fitting_options.h"

#include "bodyrec/core/model_files.h"
#include "option_checks.h"

namespace bodyrec::cli {

void ShapeFittingOptions::apply(BodyShapeModel& model) const {
  if (mask_threshold) model.set_mask_threshold(*mask_threshold);
  if (!threshold_offsets.empty()) model.set_threshold_offsets(threshold_offsets);
  if (no_mirror) model.set_mirror_average(false);
  if (no_leg_slit) model.set_leg_slit(false);
  if (no_correction) model.set_shape_correction(false);
}

std::string shape_model_path(const std::string& given) {
  if (!given.empty()) return given;
  return require_model_file(kShippedShapeModel,
                            "make one with `bodyrec make-contour-set --pennfudan DIR --out set --flip` and "
                            "`bodyrec train-shape set/train.xml --out shape.dat`, then give it with --shape");
}

void add_shape_model_option(CLI::App& sub, std::string& path) {
  sub.add_option("--shape", path, "Shape model (bodyrec train-shape); default: the shipped model " +
                                      std::string(kShippedShapeModel) + " (models/README.md)");
}

void add_shape_fitting_options(CLI::App& sub, ShapeFittingOptions& options) {
  sub.add_option("--mask-threshold", options.mask_threshold,
                 "mask-net models: the logit above which a pixel is body, instead of the model's (tune it on a "
                 "held-out set); beyond +-20 the network's output is saturated")
      ->check(in_range(-20, 20));
  sub.add_option("--threshold-offsets", options.threshold_offsets,
                 "mask-net models: average each landmark over the outlines at the threshold plus each of these "
                 "logits (0 = one outline: faster, less accurate)")
      ->delimiter(',')
      ->check(in_range(-20, 20))
      ->default_str("-2,-1,0,1,2");
  sub.add_flag("--no-mirror", options.no_mirror,
               "mask-net models: threshold the network's logits on the box alone, not their mean with its mirror "
               "image's (half the network passes: faster, slightly less accurate)");
  sub.add_flag("--no-leg-slit", options.no_leg_slit,
               "mask-net models: trace each outline without the slit cut between the legs where the logits dip");
  sub.add_flag("--no-correction", options.no_correction,
               "mask-net models: leave out the model's linear shape correction");
}

}  // namespace bodyrec::cli
