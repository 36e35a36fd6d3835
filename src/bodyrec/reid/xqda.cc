#include "bodyrec/reid/xqda.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <utility>

#include <opencv2/core.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {
namespace {

constexpr const char* kFormat = "bodyrec-xqda";
constexpr int kFormatVersion = 2;  // 2: `features` names what the model was trained on

std::string fingerprint(const cv::Mat& m) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a over the bytes
  const cv::Mat c = m.isContinuous() ? m : m.clone();
  const auto* p = c.ptr<uchar>();
  for (size_t i = 0; i < c.total() * c.elemSize(); ++i) h = (h ^ p[i]) * 1099511628211ull;
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return std::string(text, 8);
}

// Symmetric eigen-decomposition, eigenvalues descending, eigenvectors as columns.
void symmetric_eigen(const cv::Mat& m, cv::Mat& values, cv::Mat& vectors) {
  cv::Mat rows;
  cv::eigen(m, values, rows);
  vectors = rows.t();
}

// The threshold with the lowest balanced error (mean of false-accept and false-reject rates).
double balanced_threshold(std::vector<std::pair<double, bool>> d) {
  std::sort(d.begin(), d.end());
  const double same = static_cast<double>(std::count_if(d.begin(), d.end(), [](auto& p) { return p.second; }));
  const double diff = static_cast<double>(d.size()) - same;
  if (same == 0 || diff == 0) return 0;
  double accepted_same = 0, accepted_diff = 0, best = 1.0, best_t = d.front().first;
  for (size_t i = 0; i < d.size(); ++i) {
    (d[i].second ? accepted_same : accepted_diff) += 1;
    if (i + 1 < d.size() && d[i + 1].first == d[i].first) continue;
    const double err = 0.5 * ((same - accepted_same) / same + accepted_diff / diff);
    if (err < best) {
      best = err;
      best_t = i + 1 < d.size() ? 0.5 * (d[i].first + d[i + 1].first) : d[i].first;
    }
  }
  return best_t;
}

}  // namespace

void XqdaOptions::check() const {
  if (!(regulariser > 0)) throw UsageError("XQDA: regulariser must be > 0");
  if (max_dims < 0) throw UsageError("XQDA: max_dims must be >= 0");
}

double squared_distance(DescriptorView a, DescriptorView b) {
  CV_Assert(a.size == b.size);
  double s = 0;
  for (size_t i = 0; i < a.size; ++i) {
    const double d = double(a.data[i]) - b.data[i];
    s += d * d;
  }
  return s;
}

std::vector<float> XqdaModel::embed(const std::vector<float>& feature) const {
  CV_Assert(static_cast<int>(feature.size()) == projection.rows && rows.rows == projection.cols);
  // One dot product per output dimension over contiguous memory; 8 partial sums let the compiler
  // keep several multiply-adds in flight (a float reduction is not vectorised without -ffast-math).
  const int n = rows.cols;
  const float* x = feature.data();
  std::vector<float> out(static_cast<size_t>(rows.rows));
  for (int k = 0; k < rows.rows; ++k) {
    const float* w = rows.ptr<float>(k);
    float acc[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    int i = 0;
    for (; i + 8 <= n; i += 8)
      for (int j = 0; j < 8; ++j) acc[j] += w[i + j] * x[i + j];
    float sum = ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
    for (; i < n; ++i) sum += w[i] * x[i];
    out[static_cast<size_t>(k)] = sum;
  }
  return out;
}

XqdaModel train_xqda(const std::vector<XqdaSample>& samples, const XqdaOptions& options) {
  options.check();
  if (samples.empty()) throw ProcessingError("XQDA: no training samples");
  const int n = static_cast<int>(samples.size());
  const int d = static_cast<int>(samples[0].feature->size());
  cv::Mat a(n, d, CV_32F);
  for (int i = 0; i < n; ++i) {
    if (static_cast<int>(samples[i].feature->size()) != d) throw ProcessingError("XQDA: features differ in length");
    std::copy(samples[i].feature->begin(), samples[i].feature->end(), a.ptr<float>(i));
  }
  // 1. The samples span at most n dimensions: work in an orthonormal basis of their span, from the
  //    eigen-decomposition of the Gram matrix (coordinates of sample i = row i of U S^(1/2)).
  cv::Mat gram32, gram, s, u;
  cv::gemm(a, a, 1.0, cv::noArray(), 0.0, gram32, cv::GEMM_2_T);
  gram32.convertTo(gram, CV_64F);
  symmetric_eigen(gram, s, u);
  int r = 0;
  while (r < n && s.at<double>(r) > 1e-9 * s.at<double>(0)) ++r;
  cv::Mat y(n, r, CV_64F);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < r; ++j) y.at<double>(i, j) = u.at<double>(i, j) * std::sqrt(s.at<double>(j));

  // 2. Same-person and different-person covariances of cross-camera differences, without forming pairs.
  std::map<int, std::pair<int, int>> count;  // identity -> (camera 0 count, camera 1 count)
  for (const auto& smp : samples) (smp.camera == 0 ? count[smp.identity].first : count[smp.identity].second)++;
  cv::Mat sum_intra = cv::Mat::zeros(r, r, CV_64F), sum_all = cv::Mat::zeros(r, r, CV_64F);
  cv::Mat sx = cv::Mat::zeros(1, r, CV_64F), sz = cv::Mat::zeros(1, r, CV_64F);
  std::map<int, std::pair<cv::Mat, cv::Mat>> class_sums;
  double nx = 0, nz = 0, n_intra = 0;
  for (const auto& [id, c] : count) {
    n_intra += double(c.first) * c.second;
    class_sums[id] = {cv::Mat::zeros(1, r, CV_64F), cv::Mat::zeros(1, r, CV_64F)};
  }
  for (int i = 0; i < n; ++i) {
    const cv::Mat row = y.row(i);
    const bool probe_side = samples[i].camera == 0;
    const auto& c = count[samples[i].identity];
    const double other = probe_side ? c.second : c.first;  // same-identity partners in the other camera
    cv::Mat outer = row.t() * row;
    sum_intra += other * outer;
    (probe_side ? sx : sz) += row;
    (probe_side ? class_sums[samples[i].identity].first : class_sums[samples[i].identity].second) += row;
    (probe_side ? nx : nz) += 1;
  }
  if (nx == 0 || nz == 0) throw ProcessingError("XQDA: training needs images from both cameras");
  if (n_intra < 2) throw ProcessingError("XQDA: training needs at least two identities seen by both cameras");
  cv::Mat xtx = cv::Mat::zeros(r, r, CV_64F), ztz = cv::Mat::zeros(r, r, CV_64F);
  for (int i = 0; i < n; ++i) {
    const cv::Mat row = y.row(i);
    (samples[i].camera == 0 ? xtx : ztz) += row.t() * row;
  }
  sum_all = nz * xtx + nx * ztz - sx.t() * sz - sz.t() * sx;
  for (const auto& [id, sums] : class_sums) sum_intra -= sums.first.t() * sums.second + sums.second.t() * sums.first;
  const double n_extra = nx * nz - n_intra;
  if (n_extra < 1) throw ProcessingError("XQDA: training needs at least two identities");
  cv::Mat cov_intra = sum_intra / n_intra;
  cv::Mat cov_extra = (sum_all - sum_intra) / n_extra;
  cov_intra += cv::Mat::eye(r, r, CV_64F) * options.regulariser;

  // 3. Generalised eigenproblem cov_extra w = lambda cov_intra w, by whitening cov_intra.
  cv::Mat di, vi;
  symmetric_eigen(cov_intra, di, vi);
  cv::Mat whiten(r, r, CV_64F);
  for (int j = 0; j < r; ++j) {
    cv::Mat col = whiten.col(j);
    col = vi.col(j) / std::sqrt(std::max(di.at<double>(j), 1e-12));
  }
  cv::Mat c = whiten.t() * cov_extra * whiten;
  c = 0.5 * (c + c.t());
  cv::Mat lambda, v;
  symmetric_eigen(c, lambda, v);
  int k = 0;
  while (k < r && lambda.at<double>(k) > 1.0) ++k;
  if (options.max_dims > 0) k = std::min(k, options.max_dims);
  if (k == 0) throw ProcessingError("XQDA: no direction separates different people better than the same person");
  // Scale each direction by sqrt(1 - 1/lambda): M = I - diag(1/lambda) in the whitened basis.
  cv::Mat b = whiten * v.colRange(0, k);
  for (int j = 0; j < k; ++j) b.col(j) *= std::sqrt(1.0 - 1.0 / lambda.at<double>(j));

  // 4. Back to feature space: P = A^T U S^(-1/2) B.
  cv::Mat u_scaled(n, r, CV_64F);
  for (int j = 0; j < r; ++j) {
    cv::Mat col = u_scaled.col(j);
    col = u.col(j) / std::sqrt(s.at<double>(j));
  }
  const cv::Mat coef = u_scaled.colRange(0, r) * b;
  cv::Mat coef32;
  coef.convertTo(coef32, CV_32F);
  XqdaModel model;
  cv::gemm(a, coef32, 1.0, cv::noArray(), 0.0, model.projection, cv::GEMM_1_T);
  model.prepare();

  // 5. Threshold at the lowest balanced error on the training pairs.
  cv::Mat emb = y * b;
  std::vector<std::pair<double, bool>> dist;
  for (int i = 0; i < n; ++i) {
    if (samples[i].camera != 0) continue;
    for (int j = 0; j < n; ++j) {
      if (samples[j].camera == 0) continue;
      const double dd = cv::norm(emb.row(i), emb.row(j), cv::NORM_L2SQR);
      dist.emplace_back(dd, samples[i].identity == samples[j].identity);
    }
  }
  model.threshold = balanced_threshold(std::move(dist));
  return model;
}

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
    fs.open(path, cv::FileStorage::WRITE);
  } catch (const cv::Exception&) {
  }
  if (!fs.isOpened()) throw ProcessingError(path + ": cannot write the model");
  fs << "format" << kFormat << "format_version" << kFormatVersion << "id" << id << "features" << features
     << "threshold" << threshold;
  fs << "parts" << "[";
  for (const auto& p : parts) fs << "{" << "threshold" << p.threshold << "projection" << p.projection << "}";
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
  if (version != kFormatVersion)
    throw InputError(path + ": unsupported 'format_version' " + std::to_string(version) + " (this build reads " +
                     std::to_string(kFormatVersion) + "; train the model again with bodyrec train-reid)");
  XqdaEnsemble e;
  fs["threshold"] >> e.threshold;
  fs["id"] >> e.id;
  fs["features"] >> e.features;
  if (e.features.empty()) throw InputError(path + ": field 'features' is missing");
  const cv::FileNode parts = fs["parts"];
  if (!parts.isSeq() || parts.size() == 0) throw InputError(path + ": field 'parts' is missing or empty");
  for (const auto& node : parts) {
    XqdaModel m;
    node["projection"] >> m.projection;
    node["threshold"] >> m.threshold;
    if (m.projection.empty() || m.projection.type() != CV_32F)
      throw InputError(path + ": field 'parts/projection' is missing or not a float matrix");
    m.prepare();
    e.parts.push_back(m);
  }
  return e;
}

namespace {

XqdaEnsemble train_parts(const std::vector<XqdaSample>& samples, int slices, const XqdaOptions& options) {
  if (samples.empty() || slices < 1) throw ProcessingError("XQDA: no training samples");
  const size_t length = samples[0].feature->size();
  if (length % static_cast<size_t>(slices) != 0) throw ProcessingError("XQDA: features do not split into equal slices");
  const size_t part = length / static_cast<size_t>(slices);
  XqdaEnsemble e;
  for (int k = 0; k < slices; ++k) {
    std::vector<std::vector<float>> sliced(samples.size());
    std::vector<XqdaSample> sub = samples;
    for (size_t i = 0; i < samples.size(); ++i) {
      const auto begin = samples[i].feature->begin() + static_cast<long>(part * static_cast<size_t>(k));
      sliced[i].assign(begin, begin + static_cast<long>(part));
      sub[i].feature = &sliced[i];
    }
    e.parts.push_back(train_xqda(sub, options));
  }
  return e;
}

// Fused distances of every cross-camera pair of `samples` (camera 0 x camera 1), flagged same person.
std::vector<std::pair<double, bool>> cross_pairs(const XqdaEnsemble& e, const std::vector<XqdaSample>& samples) {
  std::vector<std::vector<float>> embedded;
  for (const auto& s : samples) embedded.push_back(e.embed(*s.feature));
  std::vector<std::pair<double, bool>> dist;
  for (size_t i = 0; i < samples.size(); ++i)
    for (size_t j = 0; j < samples.size(); ++j)
      if (samples[i].camera == 0 && samples[j].camera == 1)
        dist.emplace_back(squared_distance(embedded[i], embedded[j]), samples[i].identity == samples[j].identity);
  return dist;
}

// Median distance of the different-person pairs: the model's own distance scale, measured on its
// training data. Different-person pairs are hardly fitted (they are the bulk, and XQDA only whitens the
// same-person spread), so this scale carries over from a model to unseen people far better than the
// training same-person pairs, which a model with as many dimensions as samples pulls together.
double different_person_scale(const std::vector<std::pair<double, bool>>& pairs) {
  std::vector<double> d;
  for (const auto& [dist, same] : pairs)
    if (!same) d.push_back(dist);
  if (d.empty()) return 0;
  std::nth_element(d.begin(), d.begin() + static_cast<long>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

// Balanced-error threshold for people a model has not seen, from `folds`-fold cross-validation over the
// identities in `both` (each fold's model trained on the other folds, scored on the held-out pairs), in
// units of each fold model's different-person scale. 0 when it cannot be measured.
double held_out_units(const std::vector<XqdaSample>& samples, const std::vector<int>& both, int folds, int slices,
                      const XqdaOptions& options) {
  std::vector<std::pair<double, bool>> pairs;
  for (int fold = 0; fold < folds; ++fold) {
    std::vector<XqdaSample> fit, held_out;
    for (const auto& s : samples) {
      const auto it = std::lower_bound(both.begin(), both.end(), s.identity);
      const bool hold = it != both.end() && *it == s.identity && (it - both.begin()) % folds == fold;
      (hold ? held_out : fit).push_back(s);
    }
    const XqdaEnsemble model = train_parts(fit, slices, options);
    const double scale = different_person_scale(cross_pairs(model, fit));
    if (!(scale > 0)) return 0;
    for (auto [dist, same] : cross_pairs(model, held_out)) pairs.emplace_back(dist / scale, same);
  }
  return balanced_threshold(std::move(pairs));
}

}  // namespace

XqdaEnsemble train_xqda_ensemble(const std::vector<XqdaSample>& samples, int slices, const XqdaOptions& options) {
  XqdaEnsemble e = train_parts(samples, slices, options);
  const auto training_pairs = cross_pairs(e, samples);
  e.threshold = balanced_threshold(training_pairs);  // fallback: far too strict for unseen people
  // The threshold must hold for people the model has not seen. Cross-validation over the identities
  // present in both cameras measures it for models trained on fewer people, in units of each model's
  // different-person scale; those units still depend on how many people a model was trained on (with
  // fewer training images than dimensions, the metric pulls its own training pairs together), so they
  // are measured at 1/2 (2 folds) and 3/4 (4 folds) of the identities and extrapolated linearly to all
  // of them, then turned into the full model's distance by its own scale. Measured on VIPeR and on the
  // synthetic data of xqda_test.cc; docs/benchmarks.md has the figures.
  std::map<int, int> cameras;  // identity -> bit mask of cameras
  for (const auto& s : samples) cameras[s.identity] |= 1 << s.camera;
  std::vector<int> both;
  for (const auto& [id, mask] : cameras)
    if (mask == 3) both.push_back(id);
  const double full_scale = different_person_scale(training_pairs);
  if (both.size() >= 12 && full_scale > 0) {
    const double half = held_out_units(samples, both, 2, slices, options);
    const double three_quarters = held_out_units(samples, both, 4, slices, options);
    // Only extrapolated upwards (the rank-deficient case, VIPeR's); when the units fall with more
    // training people (a model that generalises, or noise between well separated pairs) the 3/4 figure,
    // the closest to the full model, is kept.
    const double units = three_quarters + std::max(0.0, three_quarters - half);
    if (half > 0 && three_quarters > 0 && units > 0) e.threshold = units * full_scale;
  }
  cv::Mat all;
  for (const auto& p : e.parts) all.push_back(p.projection.reshape(1, 1).t());
  e.id = fingerprint(all);
  return e;
}

}  // namespace bodyrec
