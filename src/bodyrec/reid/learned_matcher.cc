#include "bodyrec/reid/learned_matcher.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/count_sketch.h"
#include "bodyrec/reid/gog_features.h"
#include "bodyrec/reid/lomo_features.h"

namespace bodyrec {
namespace {

// Feature formats (a model records the one it was trained on and is refused with another).
// lomo4: LOMO as LOMO.m computes it (three unit-norm parts); lomo4m: the same mirror-averaged;
// lomo4-gog1-cs3: the default matcher's eight blocks (default_reid_variants()), each count-sketched to a
// third of its length; lomo4-gog1: the same blocks as they are (default-full).
constexpr const char* kPublishedFeatures = "lomo4";
constexpr const char* kUnlearnedFeatures = "lomo4m";
constexpr const char* kDefaultFeatures = "lomo4-gog1-cs3";
constexpr const char* kFullFeatures = "lomo4-gog1";

// The default matcher sketches each block to 1/kSketchDivisor of its length (count_sketch.h) before
// XQDA, so its model holds that share of the projection rows; with kDefaultMaxDims dimensions per part the
// shipped file is about 1 MB (7.7 MB unsketched). Chosen among settings of that size by the inner cross-validation
// of VIPeR split 0's training people; docs/benchmarks.md gives the figures with and without.
constexpr int kSketchDivisor = 3;
constexpr const char* kPublishedVariant = "published";

// Squared Euclidean distance between lomo4m features (three unit-norm parts) below which the unlearned
// matcher calls two images the same person: the balanced-error threshold over all VIPeR cross-camera
// pairs (26.7 % balanced error; docs/benchmarks.md).
constexpr double kLomoThreshold = 2.17;

constexpr GogColour kGogColours[] = {GogColour::kRgb, GogColour::kLab, GogColour::kHsv, GogColour::kNrNg};
constexpr int kGogBlock = 7;

int gog_total_length() {
  int n = 0;
  for (GogColour c : kGogColours) n += gog_length(c);
  return n;
}

// Block lengths of the default matcher's features, in order (see default_reid_variants()).
const std::vector<int>& default_blocks() {
  static const std::vector<int> lengths = {lomo_colour_length(), lomo_texture_length(), lomo_texture_length(),
                                           lomo_colour_length(), lomo_colour_length(), lomo_texture_length(),
                                           lomo_texture_length(), gog_total_length()};
  return lengths;
}

size_t block_offset(int block) {
  const auto& l = default_blocks();
  return static_cast<size_t>(std::accumulate(l.begin(), l.begin() + block, 0));
}

// One fixed sketch per block, seeded by the block's index: what the XQDA parts read of it.
const std::vector<CountSketch>& block_sketches() {
  static const std::vector<CountSketch> sketches = [] {
    std::vector<CountSketch> s;
    for (size_t b = 0; b < default_blocks().size(); ++b) {
      const int n = default_blocks()[b];
      s.emplace_back(n, (n + kSketchDivisor - 1) / kSketchDivisor, static_cast<uint64_t>(b));
    }
    return s;
  }();
  return sketches;
}

// How the XQDA parts read each block: sketched (default) or as it is (default-full).
enum class BlockReading { kSketched, kFull };

int read_length(int block, BlockReading reading) {
  return reading == BlockReading::kSketched ? block_sketches()[static_cast<size_t>(block)].output_length()
                                            : default_blocks()[static_cast<size_t>(block)];
}

int part_length(const std::vector<int>& blocks, BlockReading reading) {
  int n = 0;
  for (int b : blocks) n += read_length(b, reading);
  return n;
}

// Block `block` of the default features `f` as the parts read it, written at `out` (read_length values).
void read_block(const std::vector<float>& f, int block, BlockReading reading, float* out) {
  const float* in = f.data() + block_offset(block);
  if (reading == BlockReading::kSketched) block_sketches()[static_cast<size_t>(block)].apply(in, out);
  else std::copy(in, in + default_blocks()[static_cast<size_t>(block)], out);
}

bool uses_gog(const XqdaVariant& v) {
  for (const auto& p : v.parts)
    if (std::find(p.begin(), p.end(), kGogBlock) != p.end()) return true;
  return false;
}

void append(std::vector<float>& out, const std::vector<float>& part) { out.insert(out.end(), part.begin(), part.end()); }

class LomoGogMatcher : public AppearanceMatcher {
 public:
  LomoGogMatcher(LearnedMatcherKind kind, XqdaEnsemble model, const std::string& source)
      : kind_(kind), model_(std::move(model)) {
    if (!model_.empty()) check_model(source);
  }

  std::string name() const override {
    switch (kind_) {
      case LearnedMatcherKind::kPublished: return "lomo-xqda";
      case LearnedMatcherKind::kDefault: return "default";
      case LearnedMatcherKind::kDefaultFull: return "default-full";
      case LearnedMatcherKind::kUnlearned: break;
    }
    return "lomo";
  }
  std::string version() const override {
    return model_.empty() ? feature_format() : feature_format() + "-xqda-" + model_.id;
  }
  std::string summary() const override {
    std::ostringstream s;
    if (kind_ == LearnedMatcherKind::kUnlearned)
      s << "LOMO features (mirror-averaged), unlearned: similarity = -squared Euclidean distance, same person above -"
        << kLomoThreshold;
    else if (model_.empty())
      s << (kind_ == LearnedMatcherKind::kPublished ? "LOMO + XQDA" : "LOMO + GOG variants + XQDA") << ", not trained";
    else if (kind_ == LearnedMatcherKind::kPublished)
      s << "LOMO + XQDA as published (Liao et al. 2015; " << model_.embed_length() << " dims, model " << model_.id
        << "): similarity = -squared distance, same person above " << threshold();
    else
      s << "variant " << model_.variant << " (" << variant_description() << "; " << model_.embed_length()
        << " dims, model " << model_.id << ")" << selection_text()
        << ": similarity = -squared distance, same person above " << threshold();
    return s.str();
  }

  std::vector<float> features(const PersonImage& image) const override {
    const LomoOptions options;
    if (kind_ == LearnedMatcherKind::kPublished) return lomo_features(image, options);
    if (kind_ == LearnedMatcherKind::kUnlearned) {
      LomoOptions mirrored;
      mirrored.mirror = true;
      return lomo_features(image, mirrored);
    }
    LomoParts own;
    const LomoParts mirrored = lomo_parts(image, options, true, true, true, &own);
    std::vector<float> f;
    f.reserve(static_cast<size_t>(std::accumulate(default_blocks().begin(), default_blocks().end(), 0)));
    const std::vector<float>* blocks[] = {&own.colour[1],      &own.siltp[0],        &own.siltp[1],
                                          &mirrored.colour[0], &mirrored.colour[1], &mirrored.siltp[0],
                                          &mirrored.siltp[1]};
    for (const auto* block : blocks) append(f, *block);
    for (GogColour c : kGogColours) append(f, gog_features(image, c));
    return f;
  }

  bool learns() const override { return kind_ != LearnedMatcherKind::kUnlearned; }

  void train(const std::vector<TrainingSample>& samples) override {
    if (kind_ == LearnedMatcherKind::kUnlearned) return;
    if (kind_ == LearnedMatcherKind::kPublished) {
      XqdaOptions options;
      options.solver = XqdaSolver::kPublishedSvd;
      model_ = train_xqda_ensemble(samples, 1, options);
      model_.features = kPublishedFeatures;
      model_.variant = kPublishedVariant;
      return;
    }
    train_default(samples);
  }

  std::vector<float> descriptor(const std::vector<float>& f) const override {
    if (kind_ == LearnedMatcherKind::kUnlearned) return f;
    if (model_.empty())
      throw ProcessingError("matcher " + name() + " has no model: train it (bodyrec train-reid) or give --model");
    if (kind_ == LearnedMatcherKind::kPublished) return model_.embed(f);
    return model_.embed(gather(prepared(f, model_.feature_mean), variant(), reading()));
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
  std::string feature_format() const {
    switch (kind_) {
      case LearnedMatcherKind::kPublished: return kPublishedFeatures;
      case LearnedMatcherKind::kDefault: return kDefaultFeatures;
      case LearnedMatcherKind::kDefaultFull: return kFullFeatures;
      case LearnedMatcherKind::kUnlearned: break;
    }
    return kUnlearnedFeatures;
  }

  BlockReading reading() const {
    return kind_ == LearnedMatcherKind::kDefaultFull ? BlockReading::kFull : BlockReading::kSketched;
  }

  const XqdaVariant& variant() const {
    static const std::vector<XqdaVariant> variants = default_reid_variants();
    for (const auto& v : variants)
      if (v.name == model_.variant) return v;
    throw ProcessingError("unknown re-identification variant '" + model_.variant + "'");
  }

  std::string variant_description() const {
    const XqdaVariant& v = variant();
    std::ostringstream s;
    s << v.parts.size() << (v.parts.size() == 1 ? " XQDA model" : " XQDA models fused")
      << (reading() == BlockReading::kSketched ? " on count-sketched features" : " on the full features");
    return s.str();
  }

  std::string selection_text() const {
    if (selection_.score.empty()) return "";
    std::ostringstream s;
    s.precision(3);
    s << ", chosen by " << selection_folds_ << "-fold cross-validation over the training people (held-out mAP";
    const auto variants = default_reid_variants();
    for (size_t i = 0; i < variants.size(); ++i) s << (i ? ", " : " ") << variants[i].name << " " << selection_.score[i];
    s << ")";
    return s.str();
  }

  // The default features with the GOG block centred on `mean` and each colour space's part scaled to unit
  // norm (GOG's normalisation; the LOMO blocks are unit-norm already). An empty mean leaves them as they are.
  static std::vector<float> prepared(const std::vector<float>& f, const cv::Mat& mean) {
    std::vector<float> out = f;
    if (mean.empty()) return out;
    size_t offset = block_offset(kGogBlock);
    for (GogColour c : kGogColours) {
      const size_t n = static_cast<size_t>(gog_length(c));
      double norm = 0;
      for (size_t i = 0; i < n; ++i) {
        float& x = out[offset + i];
        x -= mean.at<float>(0, static_cast<int>(offset + i - block_offset(kGogBlock)));
        norm += double(x) * x;
      }
      const float inv = norm > 0 ? static_cast<float>(1.0 / std::sqrt(norm)) : 0.0f;
      for (size_t i = 0; i < n; ++i) out[offset + i] *= inv;
      offset += n;
    }
    return out;
  }

  // The blocks of each part of `v` as the parts read them, parts in order: what the model's parts read.
  static std::vector<float> gather(const std::vector<float>& f, const XqdaVariant& v, BlockReading reading) {
    int total = 0;
    for (const auto& part : v.parts) total += part_length(part, reading);
    std::vector<float> out(static_cast<size_t>(total));
    float* at = out.data();
    for (const auto& part : v.parts)
      for (int b : part) {
        read_block(f, b, reading, at);
        at += read_length(b, reading);
      }
    return out;
  }

  void train_default(const std::vector<TrainingSample>& samples) {
    if (samples.empty()) throw ProcessingError("re-identification training: no samples");
    const size_t gog_begin = block_offset(kGogBlock), gog_n = static_cast<size_t>(gog_total_length());
    // GOG is centred on the training mean (Matsukawa et al.); only the training samples give it.
    cv::Mat mean = cv::Mat::zeros(1, static_cast<int>(gog_n), CV_32F);
    std::vector<double> sum(gog_n, 0.0);
    for (const auto& s : samples) {
      if (s.feature->size() != gog_begin + gog_n) throw ProcessingError("re-identification training: wrong feature length");
      for (size_t i = 0; i < gog_n; ++i) sum[i] += (*s.feature)[gog_begin + i];
    }
    for (size_t i = 0; i < gog_n; ++i) mean.at<float>(0, static_cast<int>(i)) = static_cast<float>(sum[i] / samples.size());
    std::vector<std::vector<float>> ready;
    std::vector<XqdaLabel> labels;
    for (const auto& s : samples) ready.push_back(prepared(*s.feature, mean)), labels.push_back({s.identity, s.camera});
    // One Gram matrix per block as the parts read it, shared by every variant and fold.
    std::vector<cv::Mat> grams;
    for (size_t b = 0; b < default_blocks().size(); ++b) {
      const int len = read_length(static_cast<int>(b), reading());
      cv::Mat a(static_cast<int>(ready.size()), len, CV_32F);
      for (size_t i = 0; i < ready.size(); ++i)
        read_block(ready[i], static_cast<int>(b), reading(), a.ptr<float>(static_cast<int>(i)));
      grams.push_back(gram_matrix(a));
    }
    XqdaOptions options;
    options.max_dims = reading() == BlockReading::kSketched ? kDefaultMaxDims : kFullMaxDims;
    const std::vector<XqdaVariant> variants = default_reid_variants();
    // Each fold holds out at least two people; with fewer than four seen by both cameras there is
    // nothing to compare on, and the first variant (the published recipe) is trained.
    std::map<int, int> cameras;
    for (const auto& l : labels) cameras[l.identity] |= 1 << (l.camera == 0 ? 0 : 1);
    const int both = static_cast<int>(std::count_if(cameras.begin(), cameras.end(), [](auto& c) { return c.second == 3; }));
    const int folds = std::min(kDefaultSelectionFolds, both / 2);
    selection_ = folds >= 2 ? select_xqda_variant(grams, labels, variants, folds, options) : XqdaSelection{};
    selection_folds_ = folds;
    const XqdaVariant& chosen = variants[static_cast<size_t>(selection_.chosen)];
    std::vector<std::vector<float>> gathered;
    for (const auto& r : ready) gathered.push_back(gather(r, chosen, reading()));
    std::vector<XqdaSample> parts_samples;
    for (size_t i = 0; i < samples.size(); ++i) parts_samples.push_back({&gathered[i], samples[i].identity, samples[i].camera});
    std::vector<int> lengths;
    for (const auto& part : chosen.parts) lengths.push_back(part_length(part, reading()));
    model_ = train_xqda_ensemble(parts_samples, lengths, options);
    model_.features = feature_format();
    model_.variant = chosen.name;
    if (uses_gog(chosen)) model_.feature_mean = mean;
  }

  void check_model(const std::string& source) const {
    const std::string again = " (train it again with bodyrec train-reid)";
    if (model_.features != feature_format()) {
      // The two default matchers' models differ in the sketch only: the other matcher reads this one.
      const std::string other = model_.features == kFullFeatures      ? " (a default-full model: use --matcher default-full)"
                                : model_.features == kDefaultFeatures ? " (a default model: use --matcher default)"
                                                                      : again;
      throw InputError(source + ": re-identification model trained on features '" + model_.features + "', matcher " +
                       name() + " computes '" + feature_format() + "'" + other);
    }
    if (kind_ == LearnedMatcherKind::kUnlearned) throw UsageError("matcher lomo takes no model");
    if (kind_ == LearnedMatcherKind::kPublished) {
      if (model_.input_length() != lomo_length())
        throw InputError(source + ": re-identification model expects features of length " +
                         std::to_string(model_.input_length()) + ", LOMO gives " + std::to_string(lomo_length()));
      return;
    }
    const auto variants = default_reid_variants();
    const auto it = std::find_if(variants.begin(), variants.end(), [&](const auto& v) { return v.name == model_.variant; });
    if (it == variants.end()) throw InputError(source + ": field 'variant' '" + model_.variant + "' is unknown" + again);
    if (it->parts.size() != model_.parts.size())
      throw InputError(source + ": variant " + model_.variant + " has " + std::to_string(it->parts.size()) +
                       " parts, the model " + std::to_string(model_.parts.size()));
    for (size_t k = 0; k < it->parts.size(); ++k) {
      const int n = part_length(it->parts[k], reading());
      if (model_.parts[k].input_length() != n)
        throw InputError(source + ": part " + std::to_string(k) + " of the model expects " +
                         std::to_string(model_.parts[k].input_length()) + " inputs, the features give " + std::to_string(n));
    }
    if (uses_gog(*it) && model_.feature_mean.cols != gog_total_length())
      throw InputError(source + ": field 'feature_mean' has " + std::to_string(model_.feature_mean.cols) +
                       " values, GOG gives " + std::to_string(gog_total_length()));
  }

  LearnedMatcherKind kind_;
  XqdaEnsemble model_;
  XqdaSelection selection_;  // of the last train(), for the summary
  int selection_folds_ = 0;
};

}  // namespace

std::vector<XqdaVariant> default_reid_variants() {
  return {
      {"lomo", {{0, 1, 2}}},                         // the published recipe
      {"lomo-mirror-2c", {{3, 5, 6}, {4, 5, 6}}},    // mirror-averaged, colours as seen and after Retinex
      {"gog", {{7}}},                                // GOG alone
      {"lomo-mirror-2c+gog", {{3, 5, 6}, {4, 5, 6}, {7}}},
  };
}

std::unique_ptr<AppearanceMatcher> make_learned_matcher(LearnedMatcherKind kind, XqdaEnsemble model,
                                                        const std::string& source) {
  return std::make_unique<LomoGogMatcher>(kind, std::move(model), source);
}

}  // namespace bodyrec
