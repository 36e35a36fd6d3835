// Internal: the dlib types behind BodyShapeModel, shared by body_shape.cc and shape_training.cc only.
#pragma once

#include <dlib/image_processing/shape_predictor.h>
#include <opencv2/core/mat.hpp>

#include "bodyrec/core/geometry.h"
#include "bodyrec/landmarks/body_shape.h"

namespace bodyrec {

struct BodyShapeModel::Impl {
  dlib::shape_predictor predictor;
};

inline dlib::rectangle to_dlib_rect(const Box& b) {
  return dlib::rectangle(std::lround(b.x), std::lround(b.y), std::lround(b.x + b.width) - 1,
                         std::lround(b.y + b.height) - 1);
}

// Builds models from a trained predictor (used by the trainer).
class ShapeModelAccess {
 public:
  static BodyShapeModel make(dlib::shape_predictor predictor) {
    BodyShapeModel model;
    model.impl_->predictor = std::move(predictor);
    return model;
  }
  static const dlib::shape_predictor& predictor(const BodyShapeModel& model) { return model.impl_->predictor; }
};

}  // namespace bodyrec
