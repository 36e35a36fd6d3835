#include "bodyrec/landmarks/shape_training.h"

#include <cmath>
#include <fstream>

#include <dlib/image_processing/shape_predictor_trainer.h>
#include <dlib/image_transforms/assign_image.h>
#include <dlib/opencv/cv_image.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/landmarks/body_shape_impl.h"
#include "bodyrec/landmarks/contour.h"

namespace bodyrec {
namespace {

cv::Mat gray_of(const cv::Mat& image) {
  if (image.type() == CV_8UC1) return image;
  cv::Mat gray;
  cv::cvtColor(image, gray, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return gray;
}

BodyShapeModel train_trees(const LandmarkDataset& data, const ShapeTrainOptions& options);
std::vector<double> arc_offsets(const BodyShapeModel& model, const LandmarkDataset& data);
ShapeCorrection shape_correction(const BodyShapeModel& model, const LandmarkDataset& data);

}  // namespace

const char* to_string(ShapeMethod method) { return method == ShapeMethod::kTrees ? "trees" : "mask-net"; }

std::optional<ShapeMethod> parse_shape_method(const std::string& text) {
  if (text == "mask-net") return ShapeMethod::kMaskNet;
  if (text == "trees") return ShapeMethod::kTrees;
  return std::nullopt;
}

void ShapeTrainOptions::check() const {
  if (method == ShapeMethod::kMaskNet) net.check();
  if (oversampling < 1) throw UsageError("--oversampling must be >= 1");
  if (!(nu > 0 && nu <= 1)) throw UsageError("--nu must be in (0, 1]");
  if (tree_depth < 1 || tree_depth > 10) throw UsageError("--tree-depth must be in [1, 10]");
  if (cascade_depth < 1) throw UsageError("--cascade-depth must be >= 1");
  if (trees_per_level < 1) throw UsageError("--trees-per-level must be >= 1");
  if (feature_pool_size < 2) throw UsageError("--feature-pool-size must be >= 2");
  if (test_splits < 1) throw UsageError("--test-splits must be >= 1");
  if (!(lambda > 0)) throw UsageError("--lambda must be > 0");
  if (!(padding >= 0)) throw UsageError("--padding must be >= 0");
  if (threads < 1) throw UsageError("--threads must be >= 1");
}

BodyShapeModel train_body_shape(const LandmarkDataset& data, const ShapeTrainOptions& options) {
  options.check();
  if (options.method == ShapeMethod::kTrees) return train_trees(data, options);
  MaskNetTrainOptions net = options.net;
  net.verbose = net.verbose || options.verbose;
  BodyShapeModel model = ShapeModelAccess::make(train_body_mask_net(data, net), data.landmarks);
  ShapeModelAccess::set_arc_offsets(model, arc_offsets(model, data));
  ShapeModelAccess::set_correction(model, shape_correction(model, data));
  return model;
}

namespace {

// Calls f(prepared image, person) for every person the model can be scored on: not ignored, with as many
// landmarks as the model, in a box of some area.
template <typename F>
void for_each_training_person(const BodyShapeModel& model, const LandmarkDataset& data, F f) {
  for (const auto& image : data.images) {
    if (image.image.empty()) continue;
    const cv::Mat prepared = model.prepare(image.image);
    for (const auto& person : image.people)
      if (!person.ignore && person.landmarks.size() == static_cast<size_t>(model.landmarks()) &&
          person.box.area() > 0)
        f(prepared, person);
  }
}

// Per landmark, the mean over the training people of where the true point lies along the fitted outline
// minus its equal-arc-length place. The fitted outline is smoother than the pixel outline the landmarks
// were numbered on, and shorter in some parts than others: without this, every point after the head
// slides back along it (on the Penn-Fudan validation people, 7.30 % -> 6.84 % of the box height).
std::vector<double> arc_offsets(const BodyShapeModel& model, const LandmarkDataset& data) {
  const size_t n = static_cast<size_t>(model.landmarks());
  std::vector<double> sum(n, 0.0);
  int people = 0;
  for_each_training_person(model, data, [&](const cv::Mat& prepared, const AnnotatedPerson& person) {
    // The outline fitting starts from: the model's own threshold, mirror-averaged logits (the default of
    // a trained network), before any offsets (fit() would average several thresholds).
    const std::vector<cv::Point2d> outline =
        ShapeModelAccess::impl(model).net->fit(prepared, person.box, static_cast<int>(n));
    for (size_t k = 0; k < n; ++k) {
      double d = project_to_closed_polyline(person.landmarks[k], outline).arc - static_cast<double>(k) / n;
      sum[k] += d - std::round(d);  // the shorter way round
    }
    ++people;
  });
  if (people == 0) return {};
  for (double& s : sum) s /= people;
  return sum;
}

// Learnt on the training people's fits as fit() makes them before the correction (every threshold
// offset, the arc offsets, mirror-averaged logits).
ShapeCorrection shape_correction(const BodyShapeModel& model, const LandmarkDataset& data) {
  CV_Assert(ShapeModelAccess::impl(model).correction.empty());  // fit() must not apply one yet
  std::vector<std::vector<cv::Point2d>> fitted, truth;
  std::vector<Box> boxes;
  for_each_training_person(model, data, [&](const cv::Mat& prepared, const AnnotatedPerson& person) {
    fitted.push_back(model.fit(prepared, person.box));
    truth.push_back(person.landmarks);
    boxes.push_back(person.box);
  });
  if (fitted.empty()) return {};
  return ShapeCorrection::learn(fitted, truth, boxes, kShapeCorrectionRidge);
}

BodyShapeModel train_trees(const LandmarkDataset& data, const ShapeTrainOptions& options) {
  dlib::array<dlib::array2d<unsigned char>> images;
  std::vector<std::vector<dlib::full_object_detection>> shapes;
  for (const auto& image : data.images) {
    std::vector<dlib::full_object_detection> people;
    for (const auto& person : image.people) {
      if (person.ignore || person.landmarks.empty()) continue;
      std::vector<dlib::point> parts;
      for (const auto& p : person.landmarks) parts.emplace_back(std::lround(p.x), std::lround(p.y));
      people.emplace_back(to_dlib_rect(person.box), parts);
    }
    if (people.empty()) continue;
    images.resize(images.size() + 1);
    dlib::assign_image(images[images.size() - 1], dlib::cv_image<unsigned char>(gray_of(image.image)));
    shapes.push_back(std::move(people));
  }
  if (shapes.empty()) throw ProcessingError("no person with landmarks to train the shape model on");

  dlib::shape_predictor_trainer trainer;
  trainer.set_oversampling_amount(static_cast<unsigned long>(options.oversampling));
  trainer.set_nu(options.nu);
  trainer.set_tree_depth(static_cast<unsigned long>(options.tree_depth));
  trainer.set_cascade_depth(static_cast<unsigned long>(options.cascade_depth));
  trainer.set_num_trees_per_cascade_level(static_cast<unsigned long>(options.trees_per_level));
  trainer.set_feature_pool_size(static_cast<unsigned long>(options.feature_pool_size));
  trainer.set_num_test_splits(static_cast<unsigned long>(options.test_splits));
  trainer.set_lambda(options.lambda);
  trainer.set_feature_pool_region_padding(options.padding);
  trainer.set_num_threads(static_cast<unsigned long>(options.threads));
  if (!options.seed.empty()) trainer.set_random_seed(options.seed);
  if (options.verbose) trainer.be_verbose();
  try {
    return ShapeModelAccess::make(trainer.train(images, shapes));
  } catch (const dlib::error& e) {
    throw ProcessingError(std::string("shape model training failed: ") + e.what());
  }
}

}  // namespace

void save_body_shape(const BodyShapeModel& model, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw ProcessingError("cannot write " + path);
  const auto& impl = ShapeModelAccess::impl(model);
  if (impl.net) {
    impl.net->save(out);
    dlib::serialize(impl.landmarks, out);
    // The correction is read only after the offsets: a model cannot have one without the other.
    CV_Assert(impl.correction.empty() || !impl.arc_offsets.empty());
    if (!impl.arc_offsets.empty()) dlib::serialize(impl.arc_offsets, out);
    if (!impl.correction.empty()) impl.correction.write(out);
  } else {
    dlib::serialize(impl.predictor, out);
  }
  out.flush();
  if (!out) throw ProcessingError("cannot write " + path);
}

}  // namespace bodyrec
