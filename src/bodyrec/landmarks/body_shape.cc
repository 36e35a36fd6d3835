#include "bodyrec/landmarks/body_shape.h"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <dlib/opencv/cv_image.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/landmarks/body_shape_impl.h"
#include "bodyrec/landmarks/contour.h"

namespace bodyrec {
namespace {

bool at_end(std::istream& in) { return in.peek() == std::char_traits<char>::eof(); }

}  // namespace

BodyShapeModel::BodyShapeModel() : impl_(std::make_unique<Impl>()) {}

// A mask-net file is its magic bytes, the network, the landmark count, then, when present (older
// files end earlier), the landmarks' arc offsets and the shape correction; anything else is read as a
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
    if (at_end(in)) return;  // written before the arc offsets
    try {
      dlib::deserialize(impl_->arc_offsets, in);
    } catch (const dlib::serialization_error&) {
      throw InputError(path + ": truncated mask-net model (arc offsets)");
    }
    if (impl_->arc_offsets.size() != static_cast<size_t>(impl_->landmarks) ||
        !std::all_of(impl_->arc_offsets.begin(), impl_->arc_offsets.end(), [](double o) { return std::abs(o) < 0.5; }))
      throw InputError(path + ": mask-net model has invalid arc offsets");
    if (at_end(in)) return;  // written before the shape correction
    impl_->correction = ShapeCorrection::read(in, impl_->landmarks, path);
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

void BodyShapeModel::set_threshold_offsets(std::vector<double> offsets) {
  if (!impl_->net) throw UsageError("--threshold-offsets applies to mask-net models only (this one has regression trees)");
  if (offsets.empty()) throw UsageError("--threshold-offsets needs at least one value");
  if (!std::all_of(offsets.begin(), offsets.end(), [](double o) { return std::isfinite(o); }))
    throw UsageError("--threshold-offsets must be finite logits");
  impl_->threshold_offsets = std::move(offsets);
}

void BodyShapeModel::set_mirror_average(bool on) {
  if (!impl_->net) throw UsageError("--no-mirror applies to mask-net models only (this one has regression trees)");
  impl_->net->set_mirror_average(on);
}

void BodyShapeModel::set_shape_correction(bool on) {
  if (!impl_->net) throw UsageError("--no-correction applies to mask-net models only (this one has regression trees)");
  impl_->use_correction = on;
}

void BodyShapeModel::set_leg_slit(bool on) {
  if (!impl_->net) throw UsageError("--no-leg-slit applies to mask-net models only (this one has regression trees)");
  impl_->net->set_leg_slit(on);
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
  if (impl_->net) {
    const auto outlines = impl_->net->fit_at(image, box, impl_->landmarks, impl_->threshold_offsets);
    // Each outline's points are equally spaced; landmark k sits arc_offsets[k] of its length further on.
    std::vector<double> at(static_cast<size_t>(impl_->landmarks));
    for (size_t k = 0; k < at.size(); ++k)
      at[k] = static_cast<double>(k) / at.size() + (impl_->arc_offsets.empty() ? 0.0 : impl_->arc_offsets[k]);
    std::vector<cv::Point2d> mean(at.size());
    for (const auto& outline : outlines) {
      const std::vector<cv::Point2d> points = impl_->arc_offsets.empty() ? outline : points_at_arc(outline, at);
      for (size_t k = 0; k < mean.size(); ++k) mean[k] += points[k] / static_cast<double>(outlines.size());
    }
    return impl_->use_correction ? impl_->correction.apply(mean, box) : mean;
  }
  CV_Assert(image.type() == CV_8UC1);
  const dlib::cv_image<unsigned char> view(image);
  const dlib::full_object_detection shape = impl_->predictor(view, to_dlib_rect(box));
  std::vector<cv::Point2d> points;
  points.reserve(shape.num_parts());
  for (unsigned long i = 0; i < shape.num_parts(); ++i) points.emplace_back(shape.part(i).x(), shape.part(i).y());
  return points;
}

}  // namespace bodyrec
