#include "bodyrec/reid/xqda.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <opencv2/core.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/xqda_kernel.h"

namespace bodyrec {
namespace {

// Symmetric eigen-decomposition, eigenvalues descending, eigenvectors as columns.
void symmetric_eigen(const cv::Mat& m, cv::Mat& values, cv::Mat& vectors) {
  cv::Mat rows;
  cv::eigen(m, values, rows);
  vectors = rows.t();
}

// Generalised eigenproblem cov_extra w = lambda cov_intra w, by whitening cov_intra; each kept direction
// scaled by sqrt(1 - 1/lambda): M = I - diag(1/lambda) in the whitened basis.
cv::Mat eigen_directions(const cv::Mat& cov_intra, const cv::Mat& cov_extra, const XqdaOptions& options, XqdaFit& fit) {
  const int r = cov_intra.rows;
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
  cv::Mat b = whiten * v.colRange(0, k);
  for (int j = 0; j < k; ++j) b.col(j) *= std::sqrt(1.0 - 1.0 / lambda.at<double>(j));
  fit.dims = k;
  return b;
}

// XQDA.m: `[V, S] = svd(inCov \ exCov)`, where MATLAB's two-output svd returns the LEFT singular
// vectors: V = left singular vectors of cov_intra^-1 cov_extra with singular value > 1 (at least one),
// M = (V^T Si V)^-1 - (V^T Se V)^-1; the embedding is V Q diag(sqrt(mu)) over M's eigenpairs (Q, mu)
// with mu > 0.
cv::Mat published_directions(const cv::Mat& cov_intra, const cv::Mat& cov_extra, const XqdaOptions& options,
                             XqdaFit& fit) {
  const int r = cov_intra.rows;
  cv::Mat a;
  cv::solve(cov_intra, cov_extra, a, cv::DECOMP_CHOLESKY);
  const cv::SVD svd(a, cv::SVD::FULL_UV);  // singular values descending
  int k = 0;
  while (k < r && svd.w.at<double>(k) > 1.0) ++k;
  k = std::max(k, 1);
  if (options.max_dims > 0) k = std::min(k, options.max_dims);
  const cv::Mat v = svd.u.colRange(0, k).clone();
  // Si is regularised (positive definite); Se may be singular in a small training set: pseudo-inverse.
  cv::Mat m = (v.t() * cov_intra * v).inv(cv::DECOMP_CHOLESKY) - (v.t() * cov_extra * v).inv(cv::DECOMP_SVD);
  m = 0.5 * (m + m.t());
  cv::Mat mu, q;
  symmetric_eigen(m, mu, q);
  int positive = 0;
  while (positive < k && mu.at<double>(positive) > 0) ++positive;
  fit.dims = k;
  fit.negative_dims = k - positive;
  if (positive == 0) throw ProcessingError("XQDA: the learned metric has no positive direction");
  cv::Mat b = v * q.colRange(0, positive);
  for (int j = 0; j < positive; ++j) b.col(j) *= std::sqrt(mu.at<double>(j));
  return b;
}

}  // namespace

namespace xqda_detail {

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

cv::Mat sub_gram(const cv::Mat& gram, const std::vector<int>& rows, const std::vector<int>& cols) {
  cv::Mat out(static_cast<int>(rows.size()), static_cast<int>(cols.size()), CV_64F);
  for (int i = 0; i < out.rows; ++i) {
    const double* g = gram.ptr<double>(rows[static_cast<size_t>(i)]);
    double* o = out.ptr<double>(i);
    for (int j = 0; j < out.cols; ++j) o[j] = g[cols[static_cast<size_t>(j)]];
  }
  return out;
}

cv::Mat embed_others(const cv::Mat& gram, const std::vector<int>& fit_rows, const XqdaFit& fit,
                     const std::vector<int>& others) {
  const cv::Mat k = sub_gram(gram, others, fit_rows);  // others x fit
  return k * fit.coefficients;
}

cv::Mat row_distances(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat d(a.rows, b.rows, CV_64F);
  for (int i = 0; i < a.rows; ++i) {
    const double* x = a.ptr<double>(i);
    for (int j = 0; j < b.rows; ++j) {
      const double* z = b.ptr<double>(j);
      double s = 0;
      for (int k = 0; k < a.cols; ++k) s += (x[k] - z[k]) * (x[k] - z[k]);
      d.at<double>(i, j) = s;
    }
  }
  return d;
}

double different_person_median(const std::vector<std::pair<double, bool>>& pairs) {
  std::vector<double> d;
  for (const auto& [dist, same] : pairs)
    if (!same) d.push_back(dist);
  if (d.empty()) return 0;
  std::nth_element(d.begin(), d.begin() + static_cast<long>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

}  // namespace xqda_detail

void XqdaOptions::check() const {
  if (!(regulariser > 0)) throw OptionError("XqdaOptions", "regulariser", "must be > 0");
  if (max_dims < 0) throw OptionError("XqdaOptions", "max_dims", "must be >= 0");
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

cv::Mat gram_matrix(const cv::Mat& features) {
  CV_Assert(features.type() == CV_32F);
  cv::Mat gram32, gram;
  cv::gemm(features, features, 1.0, cv::noArray(), 0.0, gram32, cv::GEMM_2_T);
  gram32.convertTo(gram, CV_64F);
  return gram;
}

XqdaFit fit_xqda(const cv::Mat& gram, const std::vector<XqdaLabel>& labels, const XqdaOptions& options) {
  options.check();
  const int n = gram.rows;
  CV_Assert(gram.type() == CV_64F && gram.cols == n && static_cast<int>(labels.size()) == n);
  if (n == 0) throw ProcessingError("XQDA: no training samples");
  // 1. The samples span at most n dimensions: work in an orthonormal basis of their span, from the
  //    eigen-decomposition of the Gram matrix (coordinates of sample i = row i of U S^(1/2)).
  cv::Mat s, u;
  symmetric_eigen(gram, s, u);
  int r = 0;
  while (r < n && s.at<double>(r) > 1e-9 * s.at<double>(0)) ++r;
  if (r == 0) throw ProcessingError("XQDA: the training features are all zero");
  cv::Mat y(n, r, CV_64F);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < r; ++j) y.at<double>(i, j) = u.at<double>(i, j) * std::sqrt(s.at<double>(j));

  // 2. Same-person and different-person covariances of cross-camera differences, without forming pairs.
  std::map<int, std::pair<int, int>> count;  // identity -> (camera 0 count, camera 1 count)
  for (const auto& l : labels) (l.camera == 0 ? count[l.identity].first : count[l.identity].second)++;
  cv::Mat weighted(n, r, CV_64F), side[2] = {cv::Mat::zeros(n, r, CV_64F), cv::Mat::zeros(n, r, CV_64F)};
  cv::Mat sums[2] = {cv::Mat::zeros(1, r, CV_64F), cv::Mat::zeros(1, r, CV_64F)};
  std::map<int, cv::Mat> class_sums[2];
  double nx = 0, nz = 0, n_intra = 0;
  for (const auto& [id, c] : count) {
    n_intra += double(c.first) * c.second;
    class_sums[0][id] = cv::Mat::zeros(1, r, CV_64F);
    class_sums[1][id] = cv::Mat::zeros(1, r, CV_64F);
  }
  for (int i = 0; i < n; ++i) {
    const XqdaLabel& l = labels[static_cast<size_t>(i)];
    const int cam = l.camera == 0 ? 0 : 1;
    const auto& c = count[l.identity];
    const double other = cam == 0 ? c.second : c.first;  // same-identity partners in the other camera
    weighted.row(i) = y.row(i) * std::sqrt(other);
    y.row(i).copyTo(side[cam].row(i));
    sums[cam] += y.row(i);
    class_sums[cam][l.identity] += y.row(i);
    (cam == 0 ? nx : nz) += 1;
  }
  if (nx == 0 || nz == 0) throw ProcessingError("XQDA: training needs images from both cameras");
  if (n_intra < 2) throw ProcessingError("XQDA: training needs at least two identities seen by both cameras");
  cv::Mat sum_intra = weighted.t() * weighted;
  for (const auto& [id, a] : class_sums[0]) {
    const cv::Mat& b = class_sums[1][id];
    sum_intra -= a.t() * b + b.t() * a;
  }
  const cv::Mat xtx = side[0].t() * side[0], ztz = side[1].t() * side[1];
  const cv::Mat sum_all = nz * xtx + nx * ztz - sums[0].t() * sums[1] - sums[1].t() * sums[0];
  const double n_extra = nx * nz - n_intra;
  if (n_extra < 1) throw ProcessingError("XQDA: training needs at least two identities");
  XqdaFit fit;
  cv::Mat cov_intra = sum_intra / n_intra;
  cv::Mat cov_extra = (sum_all - sum_intra) / n_extra;
  cov_intra += cv::Mat::eye(r, r, CV_64F) * options.regulariser;

  // 3. The subspace and the metric in it (XqdaSolver), folded into one projection B.
  cv::Mat b = options.solver == XqdaSolver::kPublishedSvd ? published_directions(cov_intra, cov_extra, options, fit)
                                                             : eigen_directions(cov_intra, cov_extra, options, fit);

  // 4. Back to the samples: embedding of x = B^T S^(-1/2) U^T (A x).
  cv::Mat u_scaled(n, r, CV_64F);
  for (int j = 0; j < r; ++j) {
    cv::Mat col = u_scaled.col(j);
    col = u.col(j) / std::sqrt(s.at<double>(j));
  }
  fit.coefficients = u_scaled * b;
  fit.embedded = y * b;

  // 5. Threshold at the lowest balanced error on the training pairs.
  std::vector<std::pair<double, bool>> dist;
  for (int i = 0; i < n; ++i) {
    if (labels[static_cast<size_t>(i)].camera != 0) continue;
    for (int j = 0; j < n; ++j) {
      if (labels[static_cast<size_t>(j)].camera == 0) continue;
      dist.emplace_back(cv::norm(fit.embedded.row(i), fit.embedded.row(j), cv::NORM_L2SQR),
                        labels[static_cast<size_t>(i)].identity == labels[static_cast<size_t>(j)].identity);
    }
  }
  fit.threshold = xqda_detail::balanced_threshold(std::move(dist));
  return fit;
}

XqdaModel train_xqda(const std::vector<XqdaSample>& samples, const XqdaOptions& options) {
  options.check();
  if (samples.empty()) throw ProcessingError("XQDA: no training samples");
  const int n = static_cast<int>(samples.size());
  const int d = static_cast<int>(samples[0].feature->size());
  cv::Mat a(n, d, CV_32F);
  std::vector<XqdaLabel> labels;
  for (int i = 0; i < n; ++i) {
    if (static_cast<int>(samples[i].feature->size()) != d) throw ProcessingError("XQDA: features differ in length");
    std::copy(samples[i].feature->begin(), samples[i].feature->end(), a.ptr<float>(i));
    labels.push_back({samples[i].identity, samples[i].camera});
  }
  const XqdaFit fit = fit_xqda(gram_matrix(a), labels, options);
  cv::Mat coef32;
  fit.coefficients.convertTo(coef32, CV_32F);
  XqdaModel model;
  cv::gemm(a, coef32, 1.0, cv::noArray(), 0.0, model.projection, cv::GEMM_1_T);
  model.prepare();
  model.threshold = fit.threshold;
  return model;
}

}  // namespace bodyrec
