// The body shape predictor (thesis Ch3): dlib's ensemble of regression trees (Kazemi & Sullivan 2014)
// placing the contour landmarks inside a person's box. Loading and fitting here; training in
// shape_training.h, so fitting does not need the trainer.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/core/geometry.h"

namespace bodyrec {

class BodyShapeModel {
 public:
  // Loads a dlib shape_predictor file (`bodyrec train-shape`, dlib's own trainer). Throws InputError
  // naming the file when it is missing or not a shape predictor.
  explicit BodyShapeModel(const std::string& path);
  ~BodyShapeModel();
  BodyShapeModel(BodyShapeModel&&) noexcept;

  // Landmarks of the person in `box` of `gray` (CV_8UC1; convert BGR frames once with prepare()).
  std::vector<cv::Point2d> fit(const cv::Mat& gray, const Box& box) const;
  // The grey image fit() expects (a view when `image` is already CV_8UC1).
  static cv::Mat prepare(const cv::Mat& image);
  int landmarks() const;

 private:
  friend class ShapeModelAccess;
  BodyShapeModel();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bodyrec
