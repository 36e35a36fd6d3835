#include "bodyrec/reid/appearance_matcher.h"

#include <sstream>

#include "bodyrec/core/error.h"
#include "bodyrec/core/model_files.h"
#include "bodyrec/reid/kaze_matcher.h"
#include "bodyrec/reid/learned_matcher.h"
#include "bodyrec/reid/stripe_features.h"

namespace bodyrec {
namespace {

// Copies of the descriptors, each compared with similarity().
class CopyIndex : public DescriptorIndex {
 public:
  explicit CopyIndex(const AppearanceMatcher& matcher) : matcher_(matcher) {}
  size_t size() const override { return rows_.size(); }
  void push_back(DescriptorView d) override { rows_.push_back(d.to_vector()); }
  void set(size_t row, DescriptorView d) override { rows_.at(row) = d.to_vector(); }
  void swap_remove(size_t row) override {
    rows_.at(row) = std::move(rows_.back());
    rows_.pop_back();
  }
  void similarities(DescriptorView probe, std::vector<double>& out) const override {
    out.resize(rows_.size());
    for (size_t i = 0; i < rows_.size(); ++i) out[i] = matcher_.similarity(probe, rows_[i]);
  }

 private:
  const AppearanceMatcher& matcher_;
  std::vector<std::vector<float>> rows_;
};

// Distance (the bands' squared Hellinger distances scaled to 8 bands, 0..8) below which the stripes
// matcher calls two scans the same person; measured on synthetic recordings (docs/benchmarks.md).
constexpr double kStripeThreshold = 2.5;

class StripeMatcher : public AppearanceMatcher {
 public:
  std::string name() const override { return "stripes"; }
  // stripes1: 8 stripes by image row; stripes2: 11 bands by height above the floor.
  std::string version() const override { return "stripes2"; }
  std::string summary() const override {
    return "HSV histograms in 0.2 m bands of height above the floor (Hellinger, over the bands both show): "
           "similarity = -distance, same person above -" + std::to_string(kStripeThreshold).substr(0, 4);
  }
  std::vector<float> features(const PersonImage& image) const override { return stripe_features(image); }
  double similarity(DescriptorView probe, DescriptorView gallery) const override {
    return similarity_of(stripe_distance(probe, gallery));
  }
  double threshold() const override { return -kStripeThreshold; }
  std::unique_ptr<DescriptorIndex> make_index() const override { return std::make_unique<Index>(); }

 private:
  // Scans that share too few bands (one shows only the head, the other only the legs) cannot be the
  // same person as far as colour can tell: the largest distance.
  static double similarity_of(std::optional<double> distance) { return -distance.value_or(StripeOptions().compared_bands); }
  class Index : public DescriptorIndex {
   public:
    size_t size() const override { return stripes_.size(); }
    void push_back(DescriptorView d) override { stripes_.push_back(d); }
    void set(size_t row, DescriptorView d) override { stripes_.set(row, d); }
    void swap_remove(size_t row) override { stripes_.swap_remove(row); }
    void similarities(DescriptorView probe, std::vector<double>& out) const override {
      std::vector<std::optional<double>> distances;
      stripes_.distances(probe, distances);
      out.resize(distances.size());
      for (size_t i = 0; i < out.size(); ++i) out[i] = similarity_of(distances[i]);
    }

   private:
    StripeIndex stripes_;
  };
};

class KazeMatcher : public AppearanceMatcher {
 public:
  std::string name() const override { return "kaze"; }
  std::string version() const override { return "kaze1"; }
  std::string summary() const override {
    return "KAZE + FLANN k-d tree, ratio 0.80, similarity = 2 x matches kept (thesis Listing 6.11), same person above 10";
  }
  std::vector<float> features(const PersonImage& image) const override {
    return pack_descriptors(kaze_descriptors(image));
  }
  double similarity(DescriptorView probe, DescriptorView gallery) const override {
    return kaze_score(unpack_descriptors(probe.to_vector()), unpack_descriptors(gallery.to_vector()));
  }
  double threshold() const override { return kKazeThreshold; }
};

}  // namespace

std::unique_ptr<DescriptorIndex> AppearanceMatcher::make_index() const { return std::make_unique<CopyIndex>(*this); }

void AppearanceMatcher::save_model(const std::string& path) const {
  throw UsageError("matcher " + name() + " has no learned model to write to " + path);
}

std::vector<std::string> matcher_names() { return {"default", "default-full", "lomo-xqda", "lomo", "stripes", "kaze"}; }

namespace {

[[noreturn]] void unknown_matcher(const std::string& name) {
  std::string known;
  for (const auto& n : matcher_names()) known += (known.empty() ? "" : ", ") + n;
  throw UsageError("unknown matcher '" + name + "' (known: " + known + ")");
}

}  // namespace

std::unique_ptr<AppearanceMatcher> make_untrained_matcher(const std::string& name) {
  if (name == "kaze") return std::make_unique<KazeMatcher>();
  if (name == "stripes") return std::make_unique<StripeMatcher>();
  if (name == "lomo") return make_learned_matcher(LearnedMatcherKind::kUnlearned);
  if (name == "lomo-xqda") return make_learned_matcher(LearnedMatcherKind::kPublished);
  if (name == "default") return make_learned_matcher(LearnedMatcherKind::kDefault);
  if (name == "default-full") return make_learned_matcher(LearnedMatcherKind::kDefaultFull);
  unknown_matcher(name);
}

std::unique_ptr<AppearanceMatcher> make_matcher(const std::string& name, const std::string& model_path) {
  if (name == "kaze" || name == "lomo" || name == "stripes") {
    if (!model_path.empty()) throw UsageError("matcher " + name + " takes no model");
    return make_untrained_matcher(name);
  }
  if (name == "lomo-xqda") {
    if (model_path.empty())
      throw UsageError("matcher lomo-xqda needs --model (train one with bodyrec train-reid --matcher lomo-xqda)");
    return make_learned_matcher(LearnedMatcherKind::kPublished, XqdaEnsemble::load(model_path), model_path);
  }
  if (name == "default-full") {
    if (model_path.empty())
      throw UsageError("matcher default-full needs --model (train one with bodyrec train-reid --matcher default-full)");
    return make_learned_matcher(LearnedMatcherKind::kDefaultFull, XqdaEnsemble::load(model_path), model_path);
  }
  if (name == "default") {
    const std::string path =
        !model_path.empty() ? model_path
                            : require_model_file(kShippedReidModel,
                                                 "it is shipped in models/ (reinstall, or make it again with "
                                                 "`make reid-model`), or train one on your own people with "
                                                 "bodyrec train-reid (models/README.md)");
    return make_learned_matcher(LearnedMatcherKind::kDefault, XqdaEnsemble::load(path), path);
  }
  unknown_matcher(name);
}

}  // namespace bodyrec
