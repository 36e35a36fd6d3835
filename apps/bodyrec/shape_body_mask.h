// A body mask for plain-camera re-identification from the landmark model: joins landmarks/ and reid/, which
// the library keeps apart (reid does not depend on landmarks).
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "bodyrec/landmarks/body_shape.h"
#include "bodyrec/reid/colour_scan.h"

namespace bodyrec::cli {

// The outline of a body shape model's landmarks (bodyrec train-shape), filled. `model` must outlive this.
class ShapeBodyMask : public BodyMasker {
 public:
  explicit ShapeBodyMask(const BodyShapeModel& model) : model_(model) {}
  cv::Mat mask(const cv::Mat& frame, const cv::Rect& box) override;
  std::string describe() const override;

 private:
  const BodyShapeModel& model_;
  const uchar* prepared_for_ = nullptr;  // the frame `prepared_` was made from
  cv::Mat prepared_;
};

}  // namespace bodyrec::cli
