#include "bodyrec/reid/appearance_matcher.h"

#include <sstream>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/kaze_matcher.h"
#include "bodyrec/reid/lomo_features.h"
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

// The feature format of the LOMO matchers: a model trained on other features is refused.
// lomo2: LOMO of the colours as seen and after Retinex; lomo3: the same, each averaged with the mirror
// image's feature.
constexpr const char* kLomoFeatures = "lomo3";

// Squared Euclidean distance between LOMO features (two halves, each with a unit-norm colour and texture
// part) below which the unlearned fallback calls two images the same person: the balanced-error threshold
// over all VIPeR cross-camera pairs (3.81 for the lomo2 features).
constexpr double kLomoThreshold = 3.51;

class LomoMatcher : public AppearanceMatcher {
 public:
  // `source` names where the model came from, for errors.
  LomoMatcher(XqdaEnsemble model, bool learns, const std::string& source = "")
      : model_(std::move(model)), learns_(learns) {
    if (model_.empty()) return;
    if (model_.features != kLomoFeatures)
      throw InputError(source + ": re-identification model trained on features '" + model_.features +
                       "', this build computes '" + kLomoFeatures + "' (train it again with bodyrec train-reid)");
    if (model_.input_length() != 2 * lomo_length())
      throw InputError(source + ": re-identification model expects features of length " +
                       std::to_string(model_.input_length()) + ", LOMO x 2 gives " + std::to_string(2 * lomo_length()));
  }
  std::string name() const override { return model_.empty() ? "lomo" : "lomo-xqda"; }
  std::string version() const override {
    return model_.empty() ? kLomoFeatures : std::string(kLomoFeatures) + "-xqda-" + model_.id;
  }
  std::string summary() const override {
    std::ostringstream s;
    if (model_.empty())
      s << "LOMO features (mirror-averaged), unlearned: similarity = -squared Euclidean distance, same person above -"
        << kLomoThreshold;
    else
      s << "LOMO features (mirror-averaged) + XQDA metric (plain and Retinex colour, fused; " << model_.embed_length()
        << " dims, model " << model_.id << "): similarity = -squared distance, same person above " << threshold();
    return s.str();
  }
  // LOMO on the colours as seen, then LOMO on Retinex colours, each averaged with the mirror image's
  // (left-right invariant; on four VIPeR development splits rank-1 went from 39.9 to 41.8 %, training
  // cost unchanged: docs/benchmarks.md): one XQDA model per half, fused.
  std::vector<float> features(const PersonImage& image) const override {
    LomoOptions plain, retinex;
    plain.retinex = false;
    plain.mirror = retinex.mirror = true;
    std::vector<float> f = lomo_features(image, plain);
    const std::vector<float> r = lomo_features(image, retinex);
    f.insert(f.end(), r.begin(), r.end());
    return f;
  }
  void train(const std::vector<TrainingSample>& samples) override {
    if (!learns_) return;
    model_ = train_xqda_ensemble(samples, 2);
    model_.features = kLomoFeatures;
  }
  std::vector<float> descriptor(const std::vector<float>& f) const override {
    return model_.empty() ? f : model_.embed(f);
  }
  double similarity(DescriptorView probe, DescriptorView gallery) const override {
    return -squared_distance(probe, gallery);
  }
  double threshold() const override { return model_.empty() ? -kLomoThreshold : -model_.threshold; }
  void save_model(const std::string& path) const override {
    if (model_.empty()) AppearanceMatcher::save_model(path);
    model_.save(path);
  }

 private:
  XqdaEnsemble model_;
  bool learns_;  // false: the unlearned fallback stays unlearned
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

std::vector<std::string> matcher_names() { return {"default", "lomo-xqda", "lomo", "stripes", "kaze"}; }

std::unique_ptr<AppearanceMatcher> make_matcher(const std::string& name, const std::string& model_path) {
  if (name == "kaze" || name == "lomo" || name == "stripes") {
    if (!model_path.empty()) throw UsageError("matcher " + name + " takes no model");
    if (name == "kaze") return std::make_unique<KazeMatcher>();
    if (name == "stripes") return std::make_unique<StripeMatcher>();
    return std::make_unique<LomoMatcher>(XqdaEnsemble{}, false);
  }
  if (name == "default" || name == "lomo-xqda")
    return std::make_unique<LomoMatcher>(model_path.empty() ? XqdaEnsemble{} : XqdaEnsemble::load(model_path), true,
                                         model_path);
  std::string known;
  for (const auto& n : matcher_names()) known += (known.empty() ? "" : ", ") + n;
  throw UsageError("unknown matcher '" + name + "' (known: " + known + ")");
}

}  // namespace bodyrec
