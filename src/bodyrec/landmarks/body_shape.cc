#include "bodyrec/landmarks/body_shape.h"

#include <cmath>
#include <fstream>

#include <dlib/opencv/cv_image.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/landmarks/body_shape_impl.h"

namespace bodyrec {

BodyShapeModel::BodyShapeModel() : impl_(std::make_unique<Impl>()) {}

// A mask-net file is its magic bytes, the network, then the landmark count; anything else is read as a
// dlib shape_predictor.
BodyShapeModel::BodyShapeModel(const std::string& path) : BodyShapeModel() {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read shape model " + path);
  if (BodyMaskNet::recognise(in)) {
    impl_->net = std::make_unique<BodyMaskNet>(in, path);
    try {
      dlib::deserialize(impl_->landmarks, in);
    } catch (const dlib::serialization_error&) {
      throw InputError(path + ": truncated mask-net model (no landmark count)");
    }
    if (impl_->landmarks < 3 || impl_->landmarks > 10000)
      throw InputError(path + ": mask-net model has an invalid landmark count");
    return;
  }
  try {
    dlib::deserialize(impl_->predictor, in);
  } catch (const std::exception& e) {
    std::string why = e.what();
    why = why.substr(0, why.find('\n'));
    throw InputError(path + ": neither a dlib shape predictor nor a bodyrec mask-net model (" + why + ")");
  }
  if (impl_->predictor.num_parts() == 0) throw InputError(path + ": shape predictor has no landmarks");
  impl_->landmarks = static_cast<int>(impl_->predictor.num_parts());
}

BodyShapeModel::~BodyShapeModel() = default;
BodyShapeModel::BodyShapeModel(BodyShapeModel&&) noexcept = default;

int BodyShapeModel::landmarks() const { return impl_->landmarks; }
BodyShapeModel::Kind BodyShapeModel::kind() const { return impl_->net ? Kind::kMaskNet : Kind::kTrees; }
std::string BodyShapeModel::kind_name() const { return impl_->net ? "mask-net" : "trees"; }

void BodyShapeModel::set_mask_threshold(double logit) {
  if (!impl_->net) throw UsageError("--mask-threshold applies to mask-net models only (this one has regression trees)");
  if (!std::isfinite(logit)) throw UsageError("--mask-threshold must be a finite logit");
  impl_->net->set_threshold(logit);
}

cv::Mat BodyShapeModel::prepare(const cv::Mat& image) const {
  const int wanted = impl_->net ? CV_8UC3 : CV_8UC1;
  if (image.type() == wanted) return image;
  cv::Mat converted;
  if (impl_->net)
    cv::cvtColor(image, converted, image.channels() == 4 ? cv::COLOR_BGRA2BGR : cv::COLOR_GRAY2BGR);
  else
    cv::cvtColor(image, converted, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return converted;
}

std::vector<cv::Point2d> BodyShapeModel::fit(const cv::Mat& image, const Box& box) const {
  if (impl_->net) return impl_->net->fit(image, box, impl_->landmarks);
  CV_Assert(image.type() == CV_8UC1);
  const dlib::cv_image<unsigned char> view(image);
  const dlib::full_object_detection shape = impl_->predictor(view, to_dlib_rect(box));
  std::vector<cv::Point2d> points;
  points.reserve(shape.num_parts());
  for (unsigned long i = 0; i < shape.num_parts(); ++i) points.emplace_back(shape.part(i).x(), shape.part(i).y());
  return points;
}

}  // namespace bodyrec
