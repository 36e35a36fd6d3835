// How a mask-net shape model fits (body_shape.h): shared by `landmark` (speed against accuracy) and
// `eval landmarks` (measuring what each part of the fit is worth). Trees models take none of them.
#pragma once

#include <optional>
#include <vector>

#include <CLI/CLI.hpp>

#include "bodyrec/landmarks/body_shape.h"

namespace bodyrec::cli {

struct ShapeFittingOptions {
  std::optional<double> mask_threshold;
  std::vector<double> threshold_offsets;  // empty = the model's default
  bool no_mirror = false, no_leg_slit = false, no_correction = false;

  // Sets them on `model`; throws UsageError (naming the option) for a trees model or a bad value.
  void apply(BodyShapeModel& model) const;
};

// --mask-threshold, --threshold-offsets, --no-mirror, --no-leg-slit, --no-correction.
void add_shape_fitting_options(CLI::App& sub, ShapeFittingOptions& options);

// The shipped body shape model (models/README.md), or `given` when not empty. InputError naming the folders
// searched and how to make one when it is not installed.
std::string shape_model_path(const std::string& given);

// --shape FILE, defaulting to the shipped model.
void add_shape_model_option(CLI::App& sub, std::string& path);

}  // namespace bodyrec::cli
