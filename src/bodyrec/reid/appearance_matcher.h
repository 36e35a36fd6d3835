// One interface for comparing person images, so the online pipeline, the gallery and `eval reid` do
// not depend on which descriptor is used. A descriptor is a std::vector<float> (stored as a blob) tagged
// with name() and version(): descriptors are comparable only when both strings are equal.
//
// Convention: similarity(probe, gallery) is HIGHER for more alike images, and
// similarity > threshold() means "same person" (for kaze: the thesis's score > 10).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bodyrec/reid/descriptor_view.h"
#include "bodyrec/reid/person_image.h"
#include "bodyrec/reid/xqda.h"

namespace bodyrec {

using TrainingSample = XqdaSample;  // features, identity, camera (0 probe side / 1 gallery side)

// Stored descriptors of one matcher prepared for comparing many probes with them (one gallery view):
// similarities() gives, per row, what the matcher's similarity(probe, row) gives, up to float rounding.
// Rows are kept in the order they were added; swap_remove moves the last row into the freed place.
class DescriptorIndex {
 public:
  virtual ~DescriptorIndex() = default;
  virtual size_t size() const = 0;
  virtual void push_back(DescriptorView descriptor) = 0;
  virtual void set(size_t row, DescriptorView descriptor) = 0;
  virtual void swap_remove(size_t row) = 0;
  // out[i] = similarity(probe, row i); out is resized to size().
  virtual void similarities(DescriptorView probe, std::vector<double>& out) const = 0;
};

class AppearanceMatcher {
 public:
  virtual ~AppearanceMatcher() = default;
  virtual std::string name() const = 0;     // "default", "default-full", "lomo-xqda", "lomo", "stripes", "kaze"
  virtual std::string version() const = 0;  // descriptor format (and model fingerprint when learned)
  virtual std::string summary() const = 0;  // one line for reports: method, similarity, threshold

  // Model-independent features of one image (what train() learns from).
  virtual std::vector<float> features(const PersonImage& image) const = 0;
  // Whether train() learns anything (and descriptor() needs a model).
  virtual bool learns() const { return false; }
  // Learns from labelled features (two cameras). Matchers that learn nothing ignore it.
  virtual void train(const std::vector<TrainingSample>& samples) { (void)samples; }
  // The descriptor to store: features with the learned model, if any, applied.
  virtual std::vector<float> descriptor(const std::vector<float>& features) const { return features; }
  std::vector<float> describe(const PersonImage& image) const { return descriptor(features(image)); }

  // REQUIRES both from this matcher (same name and version).
  virtual double similarity(DescriptorView probe, DescriptorView gallery) const = 0;
  virtual double threshold() const = 0;
  // An empty index for this matcher's descriptors. The default keeps copies and calls similarity() per
  // row; "stripes" keeps only the non-zero bins, many times cheaper to search.
  virtual std::unique_ptr<DescriptorIndex> make_index() const;

  // Writes the learned model (cv::FileStorage YAML) for make_matcher(name, path); throws UsageError
  // when this matcher has nothing learned to save.
  virtual void save_model(const std::string& path) const;
};

// The matchers by name (learned_matcher.h has the LOMO-based ones):
//  "default": LOMO and GOG features with XQDA; train() picks one of a few fixed variants (plain LOMO,
//      mirror-averaged LOMO of two colour versions fused, GOG, both fused) by cross-validation over the
//      training people only. Its model: model_path, else the shipped one (models/, kShippedReidModel,
//      found by find_model_file; InputError saying how to get one when there is none).
//      similarity = -squared distance of the embeddings, threshold calibrated on held-out training
//      people (train_xqda_ensemble).
//  "default-full": the same on the full (unsketched) features, up to 100 dimensions per part; nothing
//      shipped (its model is about 7.7 MB): needs model_path (else UsageError).
//  "lomo-xqda": the published LOMO + XQDA (Liao et al. 2015); needs model_path (else UsageError).
//  "lomo": mirror-averaged LOMO, similarity = -squared Euclidean distance, threshold measured on VIPeR.
//  "stripes": compact colour histograms in horizontal stripes (stripe_features.h), no model; the online
//      default of `bodyrec reid` (4 KB per scan), threshold set on synthetic recordings.
//  "kaze": the thesis's KAZE score (kaze_matcher.h), threshold 10.
// Throws UsageError for an unknown name or a model given to a matcher that takes none, InputError for an
// unreadable model or one trained on other features (an XQDA model records them, e.g. "lomo4-gog1-cs3").
std::unique_ptr<AppearanceMatcher> make_matcher(const std::string& name, const std::string& model_path = "");

// The same matcher without a model, to be trained (eval reid's splits, train-reid): "default",
// "default-full" and "lomo-xqda" then need train() before descriptor(); the others are as make_matcher
// makes them.
std::unique_ptr<AppearanceMatcher> make_untrained_matcher(const std::string& name);

// The names make_matcher accepts, for --help and errors.
std::vector<std::string> matcher_names();

}  // namespace bodyrec
