// Internal: what is behind BodyShapeModel, shared by body_shape.cc and shape_training.cc only.
#pragma once

#include <memory>
#include <vector>

#include <dlib/image_processing/shape_predictor.h>
#include <opencv2/core/mat.hpp>

#include "bodyrec/core/geometry.h"
#include "bodyrec/landmarks/body_shape.h"
#include "bodyrec/landmarks/mask_net.h"
#include "bodyrec/landmarks/shape_correction.h"

namespace bodyrec {

struct BodyShapeModel::Impl {
  dlib::shape_predictor predictor;  // kind kTrees
  std::unique_ptr<BodyMaskNet> net;  // kind kMaskNet (when set)
  int landmarks = 0;
  // Mask network: per landmark, where it lies along the fitted outline beyond its equal-arc-length place
  // (a fraction of the outline's length, measured on the training people); empty = none (older files).
  std::vector<double> arc_offsets;
  // Mask network: fit() averages each landmark over the outlines at the model's threshold plus each of
  // these logit offsets (BodyShapeModel::set_threshold_offsets).
  std::vector<double> threshold_offsets = kDefaultThresholdOffsets;
  // Mask network: applied to the averaged landmarks (empty = none: older files); `use_correction` is
  // BodyShapeModel::set_shape_correction.
  ShapeCorrection correction;
  bool use_correction = true;
};

inline dlib::rectangle to_dlib_rect(const Box& b) {
  return dlib::rectangle(std::lround(b.x), std::lround(b.y), std::lround(b.x + b.width) - 1,
                         std::lround(b.y + b.height) - 1);
}

// Builds models from what the trainers return.
class ShapeModelAccess {
 public:
  static BodyShapeModel make(dlib::shape_predictor predictor) {
    BodyShapeModel model;
    model.impl_->landmarks = static_cast<int>(predictor.num_parts());
    model.impl_->predictor = std::move(predictor);
    return model;
  }
  static BodyShapeModel make(BodyMaskNet net, int landmarks) {
    BodyShapeModel model;
    model.impl_->net = std::make_unique<BodyMaskNet>(std::move(net));
    model.impl_->landmarks = landmarks;
    return model;
  }
  static void set_arc_offsets(BodyShapeModel& model, std::vector<double> offsets) {
    model.impl_->arc_offsets = std::move(offsets);
  }
  static void set_correction(BodyShapeModel& model, ShapeCorrection correction) {
    model.impl_->correction = std::move(correction);
  }
  static const BodyShapeModel::Impl& impl(const BodyShapeModel& model) { return *model.impl_; }
};

}  // namespace bodyrec
