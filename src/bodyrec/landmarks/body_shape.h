// The body shape model (thesis Ch3): N contour landmarks of the person inside a box. Two kinds, told apart
// by the model file: the thesis's dlib ensemble of regression trees (Kazemi & Sullivan 2014; grey image)
// and bodyrec's per-pixel body mask network (mask_net.h; colour image), whose landmarks are the mask's
// outline numbered like the training contours, each point then moved along it by the model's per-landmark
// arc offset, then corrected by a linear map of the whole shape (shape_correction.h; both learnt on the
// training people). Loading and fitting here; training in shape_training.h.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/core/geometry.h"

namespace bodyrec {

class BodyMaskNet;

// Chosen on the Penn-Fudan validation people (docs/benchmarks.md, "Several thresholds").
inline const std::vector<double> kDefaultThresholdOffsets = {-2.0, -1.0, 0.0, 1.0, 2.0};

// The body shape model bodyrec ships (models/README.md: two mask networks trained on Penn-Fudan), found with
// find_model_file (core/model_files.h).
constexpr const char* kShippedShapeModel = "body-shape.dat";

class BodyShapeModel {
 public:
  enum class Kind { kTrees, kMaskNet };

  // Loads a model written by `bodyrec train-shape` (either kind) or any dlib shape_predictor file. Throws
  // InputError naming the file when it is missing, truncated or neither kind.
  explicit BodyShapeModel(const std::string& path);
  ~BodyShapeModel();
  BodyShapeModel(BodyShapeModel&&) noexcept;

  // Landmarks of the person in `box` of `image`, which must come from prepare() (convert each frame
  // once). Not thread-safe: use one model per thread.
  std::vector<cv::Point2d> fit(const cv::Mat& image, const Box& box) const;
  // The image fit() expects from a BGR, BGRA or grey frame: grey for the trees, BGR for the mask network
  // (a view when `image` already is one).
  cv::Mat prepare(const cv::Mat& image) const;
  int landmarks() const;
  Kind kind() const;
  std::string kind_name() const;  // "trees" or "mask-net"
  // Mask network only: the logit above which a pixel is body (the model file's value until changed).
  // Throws UsageError for the trees or a value that is not finite.
  void set_mask_threshold(double logit);
  // Mask network only: fit() averages each landmark over the outlines at the threshold plus each of these
  // logit offsets (default kDefaultThresholdOffsets), hedging where the body's edge is uncertain (a gap
  // between the legs) instead of betting on one outline; {0} = the single outline. Throws UsageError for
  // the trees, an empty list or a value that is not finite.
  void set_threshold_offsets(std::vector<double> offsets);
  // Mask network only: fit() thresholds the mean of the network's logits on the box and on its mirror
  // image (true, the default) or the box's alone (BodyMaskNet::fitting_logits). Throws UsageError for
  // the trees.
  void set_mirror_average(bool on);
  // Mask network only: fit() applies the model's linear shape correction (true, the default; models
  // trained before 2026-12-03 have none) or not. Throws UsageError for the trees.
  void set_shape_correction(bool on);
  // Mask network only: before tracing each outline, fit() cuts a slit between the legs where the logits
  // dip below the threshold + kLegSlitMargin (true, the default; leg_gap.h) or not. Throws UsageError for
  // the trees.
  void set_leg_slit(bool on);

 private:
  friend class ShapeModelAccess;
  BodyShapeModel();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bodyrec
