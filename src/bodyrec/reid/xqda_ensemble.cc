// XqdaEnsemble: training (one kernel-form XQDA per slice, the fused threshold calibrated on held-out
// people through the same Gram matrices), embedding, and the model file.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <numeric>
#include <string>
#include <utility>

#include <opencv2/core.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/xqda.h"
#include "bodyrec/reid/xqda_kernel.h"

namespace bodyrec {
namespace {

using namespace xqda_detail;

constexpr const char* kFormat = "bodyrec-xqda";
// 2: `features` names what the model was trained on; 3: `variant`, `feature_mean`, float16 projections;
// 4: int8 projections with a scale per column (half the size of 3; version 3 files are still read).
constexpr int kFormatVersion = 4;
constexpr int kOldestReadableVersion = 3;

std::string fingerprint(const cv::Mat& m) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a over the bytes
  const cv::Mat c = m.isContinuous() ? m : m.clone();
  const auto* p = c.ptr<uchar>();
  for (size_t i = 0; i < c.total() * c.elemSize(); ++i) h = (h ^ p[i]) * 1099511628211ull;
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return std::string(text, 8);
}

// Version 3 files hold projections as float16 (the raw bits as 16-bit integers: FileStorage's base64
// writer has no half type).
cv::Mat from_half_bits(const cv::Mat& bits) {
  cv::Mat half(bits.size(), CV_16F, const_cast<uchar*>(bits.data)), out;
  half.convertTo(out, CV_32F);
  return out;
}

// Projections are stored as int8 with one scale per column (per embedding dimension), which keeps a
// column's largest weight exact to 1/254 of itself; the model keeps the float32 values those stand for,
// so a trained and a loaded model agree.
struct QuantisedProjection {
  cv::Mat values;  // CV_8S, the projection's size
  cv::Mat scales;  // CV_32F 1 x cols: projection(r, c) = values(r, c) * scales(c)
};
QuantisedProjection quantise(const cv::Mat& projection) {
  QuantisedProjection q{cv::Mat(projection.size(), CV_8S), cv::Mat(1, projection.cols, CV_32F)};
  for (int c = 0; c < projection.cols; ++c) {
    double largest = 0;
    cv::minMaxIdx(cv::abs(projection.col(c)), nullptr, &largest);
    const float scale = largest > 0 ? static_cast<float>(largest / 127.0) : 1.0f;
    q.scales.at<float>(c) = scale;
    for (int r = 0; r < projection.rows; ++r)
      q.values.at<int8_t>(r, c) = static_cast<int8_t>(std::lround(projection.at<float>(r, c) / scale));
  }
  return q;
}
cv::Mat dequantise(const QuantisedProjection& q) {
  cv::Mat out(q.values.size(), CV_32F);
  for (int r = 0; r < out.rows; ++r)
    for (int c = 0; c < out.cols; ++c) out.at<float>(r, c) = q.values.at<int8_t>(r, c) * q.scales.at<float>(c);
  return out;
}

// The training data of one slice for the kernel form: its Gram matrix over all samples.
struct Slices {
  std::vector<cv::Mat> features;  // CV_32F n x slice length
  std::vector<cv::Mat> grams;     // CV_64F n x n
  std::vector<XqdaLabel> labels;
};

Slices slice_samples(const std::vector<XqdaSample>& samples, const std::vector<int>& lengths) {
  if (samples.empty()) throw ProcessingError("XQDA: no training samples");
  const size_t total = static_cast<size_t>(std::accumulate(lengths.begin(), lengths.end(), 0));
  Slices s;
  for (const auto& smp : samples) {
    if (smp.feature->size() != total) throw ProcessingError("XQDA: features do not match the slice lengths");
    s.labels.push_back({smp.identity, smp.camera});
  }
  size_t offset = 0;
  for (int len : lengths) {
    if (len < 1) throw ProcessingError("XQDA: empty slice");
    cv::Mat a(static_cast<int>(samples.size()), len, CV_32F);
    for (size_t i = 0; i < samples.size(); ++i)
      std::copy(samples[i].feature->begin() + static_cast<long>(offset),
                samples[i].feature->begin() + static_cast<long>(offset) + len, a.ptr<float>(static_cast<int>(i)));
    offset += static_cast<size_t>(len);
    s.grams.push_back(gram_matrix(a));
    s.features.push_back(a);
  }
  return s;
}

std::vector<int> camera_rows(const std::vector<XqdaLabel>& labels, const std::vector<int>& rows, int camera) {
  std::vector<int> out;
  for (int r : rows)
    if (labels[static_cast<size_t>(r)].camera == camera) out.push_back(r);
  return out;
}

// Fused distances (each slice's distance over its own training threshold) of every camera-0 x camera-1
// pair among `pairs_of`, for models trained on `fit_rows`.
std::vector<std::pair<double, bool>> fused_pairs(const Slices& s, const std::vector<int>& fit_rows,
                                                 const std::vector<int>& pairs_of, const XqdaOptions& options) {
  const std::vector<int> cam0 = camera_rows(s.labels, pairs_of, 0), cam1 = camera_rows(s.labels, pairs_of, 1);
  const std::vector<XqdaLabel> fit_labels = [&] {
    std::vector<XqdaLabel> l;
    for (int r : fit_rows) l.push_back(s.labels[static_cast<size_t>(r)]);
    return l;
  }();
  cv::Mat fused = cv::Mat::zeros(static_cast<int>(cam0.size()), static_cast<int>(cam1.size()), CV_64F);
  for (const cv::Mat& gram : s.grams) {
    const XqdaFit fit = fit_xqda(sub_gram(gram, fit_rows, fit_rows), fit_labels, options);
    const cv::Mat d = row_distances(embed_others(gram, fit_rows, fit, cam0), embed_others(gram, fit_rows, fit, cam1));
    fused += d / std::max(fit.threshold, 1e-12);
  }
  std::vector<std::pair<double, bool>> out;
  for (int i = 0; i < fused.rows; ++i)
    for (int j = 0; j < fused.cols; ++j)
      out.emplace_back(fused.at<double>(i, j), s.labels[static_cast<size_t>(cam0[static_cast<size_t>(i)])].identity ==
                                                   s.labels[static_cast<size_t>(cam1[static_cast<size_t>(j)])].identity);
  return out;
}

// Balanced-error threshold for people a model has not seen, from `folds`-fold cross-validation over the
// identities in `both` (each fold's model trained on the other folds, scored on the held-out pairs), in
// units of each fold model's median different-person distance on its own training pairs. 0 when it
// cannot be measured.
double held_out_units(const Slices& s, const std::vector<int>& both, int folds, const XqdaOptions& options) {
  std::vector<std::pair<double, bool>> pairs;
  for (int fold = 0; fold < folds; ++fold) {
    std::vector<int> fit, held_out;
    for (size_t i = 0; i < s.labels.size(); ++i) {
      const auto it = std::lower_bound(both.begin(), both.end(), s.labels[i].identity);
      const bool hold = it != both.end() && *it == s.labels[i].identity && (it - both.begin()) % folds == fold;
      (hold ? held_out : fit).push_back(static_cast<int>(i));
    }
    const double scale = different_person_median(fused_pairs(s, fit, fit, options));
    if (!(scale > 0)) return 0;
    for (auto [dist, same] : fused_pairs(s, fit, held_out, options)) pairs.emplace_back(dist / scale, same);
  }
  return balanced_threshold(std::move(pairs));
}

}  // namespace

int XqdaEnsemble::input_length() const {
  int n = 0;
  for (const auto& p : parts) n += p.input_length();
  return n;
}

int XqdaEnsemble::embed_length() const {
  int n = 0;
  for (const auto& p : parts) n += p.projection.cols;
  return n;
}

std::vector<float> XqdaEnsemble::embed(const std::vector<float>& feature) const {
  CV_Assert(static_cast<int>(feature.size()) == input_length());
  std::vector<float> out;
  size_t offset = 0;
  for (const auto& p : parts) {
    const std::vector<float> slice(feature.begin() + static_cast<long>(offset),
                                   feature.begin() + static_cast<long>(offset) + p.input_length());
    offset += static_cast<size_t>(p.input_length());
    const float scale = static_cast<float>(1.0 / std::sqrt(std::max(p.threshold, 1e-12)));
    for (float x : p.embed(slice)) out.push_back(x * scale);
  }
  return out;
}

void XqdaEnsemble::save(const std::string& path) const {
  if (features.empty()) throw ProcessingError(path + ": the model does not say which features it was trained on");
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::WRITE | cv::FileStorage::BASE64);
  } catch (const cv::Exception&) {
  }
  if (!fs.isOpened()) throw ProcessingError(path + ": cannot write the model");
  fs << "format" << kFormat << "format_version" << kFormatVersion << "id" << id << "features" << features
     << "variant" << variant << "threshold" << threshold;
  if (!feature_mean.empty()) fs << "feature_mean" << feature_mean;
  fs << "parts" << "[";
  for (const auto& p : parts) {
    const QuantisedProjection q = quantise(p.projection);
    fs << "{" << "threshold" << p.threshold << "projection_int8" << q.values << "column_scale" << q.scales << "}";
  }
  fs << "]";
}

XqdaEnsemble XqdaEnsemble::load(const std::string& path) {
  cv::FileStorage fs;
  try {
    fs.open(path, cv::FileStorage::READ);
  } catch (const cv::Exception&) {
  }
  if (!fs.isOpened()) throw InputError(path + ": cannot read the re-identification model");
  if (static_cast<std::string>(fs["format"]) != kFormat)
    throw InputError(path + ": field 'format' is not " + std::string(kFormat));
  const int version = static_cast<int>(fs["format_version"]);
  if (version < kOldestReadableVersion || version > kFormatVersion)
    throw InputError(path + ": unsupported 'format_version' " + std::to_string(version) + " (this build reads " +
                     std::to_string(kOldestReadableVersion) + " to " + std::to_string(kFormatVersion) +
                     "; train the model again with bodyrec train-reid)");
  XqdaEnsemble e;
  try {
    fs["threshold"] >> e.threshold;
    fs["id"] >> e.id;
    fs["features"] >> e.features;
    fs["variant"] >> e.variant;
    fs["feature_mean"] >> e.feature_mean;
  } catch (const cv::Exception&) {
    throw InputError(path + ": a field of the model header cannot be read");
  }
  if (e.features.empty()) throw InputError(path + ": field 'features' is missing");
  if (!e.feature_mean.empty() && (e.feature_mean.type() != CV_32F || e.feature_mean.rows != 1))
    throw InputError(path + ": field 'feature_mean' is not a float row");
  const cv::FileNode parts = fs["parts"];
  if (!parts.isSeq() || parts.size() == 0) throw InputError(path + ": field 'parts' is missing or empty");
  for (const auto& node : parts) {
    XqdaModel m;
    if (version == 3) {
      cv::Mat bits;
      try {
        node["projection_float16"] >> bits;
        node["threshold"] >> m.threshold;
      } catch (const cv::Exception&) {
        bits = cv::Mat();
      }
      if (bits.empty() || bits.type() != CV_16U)
        throw InputError(path + ": field 'parts/projection_float16' is missing or not a float16 matrix");
      m.projection = from_half_bits(bits);
    } else {
      QuantisedProjection q;
      try {
        node["projection_int8"] >> q.values;
        node["column_scale"] >> q.scales;
        node["threshold"] >> m.threshold;
      } catch (const cv::Exception&) {
        q.values = cv::Mat();
      }
      if (q.values.empty() || q.values.type() != CV_8S)
        throw InputError(path + ": field 'parts/projection_int8' is missing or not an int8 matrix");
      if (q.scales.type() != CV_32F || q.scales.rows != 1 || q.scales.cols != q.values.cols)
        throw InputError(path + ": field 'parts/column_scale' is not a float row of one scale per column");
      m.projection = dequantise(q);
    }
    m.prepare();
    e.parts.push_back(m);
  }
  return e;
}

XqdaEnsemble train_xqda_ensemble(const std::vector<XqdaSample>& samples, const std::vector<int>& slice_lengths,
                                 const XqdaOptions& options) {
  options.check();
  const Slices s = slice_samples(samples, slice_lengths);
  std::vector<int> all(samples.size());
  std::iota(all.begin(), all.end(), 0);
  XqdaEnsemble e;
  for (size_t k = 0; k < s.grams.size(); ++k) {
    const XqdaFit fit = fit_xqda(s.grams[k], s.labels, options);
    cv::Mat coef32;
    fit.coefficients.convertTo(coef32, CV_32F);
    XqdaModel m;
    cv::gemm(s.features[k], coef32, 1.0, cv::noArray(), 0.0, m.projection, cv::GEMM_1_T);
    // Stored as int8: keep the values the file will hold, so a trained and a loaded model agree.
    m.projection = dequantise(quantise(m.projection));
    m.prepare();
    m.threshold = fit.threshold;
    e.parts.push_back(m);
  }
  const auto training_pairs = fused_pairs(s, all, all, options);
  e.threshold = balanced_threshold(training_pairs);  // fallback: far too strict for unseen people
  // The threshold must hold for people the model has not seen. Cross-validation over the identities
  // present in both cameras measures it for models trained on fewer people, in units of each model's
  // different-person scale; those units still depend on how many people a model was trained on (with
  // fewer training images than dimensions, the metric pulls its own training pairs together), so they
  // are measured at 1/2 (2 folds) and 3/4 (4 folds) of the identities and extrapolated linearly to all
  // of them, then turned into the full model's distance by its own scale. Measured on VIPeR and on the
  // synthetic data of xqda_test.cc; docs/benchmarks.md has the figures.
  std::map<int, int> cameras;  // identity -> bit mask of cameras
  for (const auto& l : s.labels) cameras[l.identity] |= 1 << (l.camera == 0 ? 0 : 1);
  std::vector<int> both;
  for (const auto& [id, mask] : cameras)
    if (mask == 3) both.push_back(id);
  const double full_scale = different_person_median(training_pairs);
  if (both.size() >= 12 && full_scale > 0) {
    const double half = held_out_units(s, both, 2, options);
    const double three_quarters = held_out_units(s, both, 4, options);
    // Only extrapolated upwards (the rank-deficient case, VIPeR's); when the units fall with more
    // training people (a model that generalises, or noise between well separated pairs) the 3/4 figure,
    // the closest to the full model, is kept.
    const double units = three_quarters + std::max(0.0, three_quarters - half);
    if (half > 0 && three_quarters > 0 && units > 0) e.threshold = units * full_scale;
  }
  cv::Mat all_projections;
  for (const auto& p : e.parts) all_projections.push_back(p.projection.reshape(1, 1).t());
  e.id = fingerprint(all_projections);
  return e;
}

XqdaEnsemble train_xqda_ensemble(const std::vector<XqdaSample>& samples, int slices, const XqdaOptions& options) {
  if (samples.empty() || slices < 1) throw ProcessingError("XQDA: no training samples");
  const int length = static_cast<int>(samples[0].feature->size());
  if (length % slices != 0) throw ProcessingError("XQDA: features do not split into equal slices");
  return train_xqda_ensemble(samples, std::vector<int>(static_cast<size_t>(slices), length / slices), options);
}

}  // namespace bodyrec
