#include "bodyrec/landmarks/body_shape.h"

#include <fstream>

#include <dlib/opencv/cv_image.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/landmarks/body_shape_impl.h"

namespace bodyrec {

BodyShapeModel::BodyShapeModel() : impl_(std::make_unique<Impl>()) {}

BodyShapeModel::BodyShapeModel(const std::string& path) : BodyShapeModel() {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read shape model " + path);
  try {
    dlib::deserialize(impl_->predictor, in);
  } catch (const std::exception& e) {
    std::string why = e.what();
    why = why.substr(0, why.find('\n'));
    throw InputError(path + ": not a dlib shape predictor (" + why + ")");
  }
  if (impl_->predictor.num_parts() == 0) throw InputError(path + ": shape predictor has no landmarks");
}

BodyShapeModel::~BodyShapeModel() = default;
BodyShapeModel::BodyShapeModel(BodyShapeModel&&) noexcept = default;

int BodyShapeModel::landmarks() const { return static_cast<int>(impl_->predictor.num_parts()); }

cv::Mat BodyShapeModel::prepare(const cv::Mat& image) {
  if (image.type() == CV_8UC1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return gray;
}

std::vector<cv::Point2d> BodyShapeModel::fit(const cv::Mat& gray, const Box& box) const {
  CV_Assert(gray.type() == CV_8UC1);
  const dlib::cv_image<unsigned char> view(gray);
  const dlib::full_object_detection shape = impl_->predictor(view, to_dlib_rect(box));
  std::vector<cv::Point2d> points;
  points.reserve(shape.num_parts());
  for (unsigned long i = 0; i < shape.num_parts(); ++i) points.emplace_back(shape.part(i).x(), shape.part(i).y());
  return points;
}

}  // namespace bodyrec
