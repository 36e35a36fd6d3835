#include "bodyrec/reid/gog_features.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/reid/resample.h"

namespace bodyrec {
namespace {

constexpr int kMaxPixelFeatures = 8;

int pixel_features(GogColour colour) { return colour == GogColour::kNrNg ? 7 : 8; }
int triangle(int n) { return n * (n + 1) / 2; }

// Per pixel: [y / height, M_0, M_90, M_180, M_270, colour...] (CV_64FC1 rows of d values per pixel).
cv::Mat pixel_feature_image(const cv::Mat& bgr, GogColour colour) {
  const int d = pixel_features(colour);
  cv::Mat f;
  bgr.convertTo(f, CV_32FC3, 1.0 / 255.0);
  cv::Mat gray, gx, gy;
  cv::cvtColor(f, gray, cv::COLOR_BGR2GRAY);
  cv::Sobel(gray, gx, CV_32F, 1, 0, 1);  // [-1 0 1], borders reflected
  cv::Sobel(gray, gy, CV_32F, 0, 1, 1);
  cv::Mat c;
  switch (colour) {
    case GogColour::kRgb: cv::cvtColor(f, c, cv::COLOR_BGR2RGB); break;
    case GogColour::kLab:  // L 0..100, a and b about -128..127
      cv::cvtColor(f, c, cv::COLOR_BGR2Lab);
      c = c.mul(cv::Scalar(1 / 100.0, 1 / 255.0, 1 / 255.0)) + cv::Scalar(0, 0.5, 0.5);
      break;
    case GogColour::kHsv:
      cv::cvtColor(f, c, cv::COLOR_BGR2HSV);
      c = c.mul(cv::Scalar(1 / 360.0, 1, 1));
      break;
    case GogColour::kNrNg: c = f; break;
  }
  cv::Mat out(bgr.rows * bgr.cols, d, CV_64F);
  constexpr double kQuarter = CV_PI / 2;
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x) {
      double* v = out.ptr<double>(y * bgr.cols + x);
      v[0] = double(y) / bgr.rows;
      const double dx = gx.at<float>(y, x), dy = gy.at<float>(y, x), magnitude = std::sqrt(dx * dx + dy * dy);
      double angle = std::atan2(dy, dx);
      if (angle < 0) angle += 2 * CV_PI;
      const double position = angle / kQuarter;
      const int bin = static_cast<int>(position) % 4;
      const double frac = position - std::floor(position);
      for (int k = 0; k < 4; ++k) v[1 + k] = 0;
      v[1 + bin] += magnitude * (1 - frac);
      v[1 + (bin + 1) % 4] += magnitude * frac;
      const cv::Vec3f p = c.at<cv::Vec3f>(y, x);
      if (colour == GogColour::kNrNg) {
        const double sum = double(p[0]) + p[1] + p[2] + 1e-6;
        v[5] = p[2] / sum, v[6] = p[1] / sum;  // normalised red and green
      } else {
        for (int k = 0; k < 3; ++k) v[5 + k] = p[k];
      }
    }
  return out;
}

// Embeds the Gaussian (mean mu, covariance cov: d x d row-major; eps added) as an SPD matrix and appends
// the upper triangle of its logarithm (off-diagonals times sqrt 2).
void append_log_gaussian(const std::vector<double>& mu, std::vector<double> cov, double eps, std::vector<double>& out) {
  const int d = static_cast<int>(mu.size()), n = d + 1;
  for (int i = 0; i < d; ++i) cov[static_cast<size_t>(i * d + i)] += eps;
  // log |cov| from its Cholesky factor; |cov|^(-1/(d+1)) scaling P adds a constant to log(P)'s diagonal.
  std::vector<double> l = cov;
  double log_det = 0;
  for (int j = 0; j < d; ++j) {
    double diag = l[static_cast<size_t>(j * d + j)];
    for (int k = 0; k < j; ++k) diag -= l[static_cast<size_t>(j * d + k)] * l[static_cast<size_t>(j * d + k)];
    diag = std::sqrt(std::max(diag, 1e-300));
    l[static_cast<size_t>(j * d + j)] = diag;
    log_det += 2 * std::log(diag);
    for (int i = j + 1; i < d; ++i) {
      double v = l[static_cast<size_t>(i * d + j)];
      for (int k = 0; k < j; ++k) v -= l[static_cast<size_t>(i * d + k)] * l[static_cast<size_t>(j * d + k)];
      l[static_cast<size_t>(i * d + j)] = v / diag;
    }
  }
  const double shift = -log_det / n;
  std::vector<double> p(static_cast<size_t>(n * n));
  for (int i = 0; i < d; ++i) {
    for (int j = 0; j < d; ++j) p[static_cast<size_t>(i * n + j)] = cov[static_cast<size_t>(i * d + j)] + mu[i] * mu[j];
    p[static_cast<size_t>(i * n + d)] = p[static_cast<size_t>(d * n + i)] = mu[i];
  }
  p[static_cast<size_t>(d * n + d)] = 1;
  cv::Mat values, vectors;  // rows of `vectors` are the eigenvectors
  cv::eigen(cv::Mat(n, n, CV_64F, p.data()), values, vectors);
  std::vector<double> logs(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) logs[static_cast<size_t>(k)] = std::log(std::max(values.at<double>(k), 1e-300));
  for (int i = 0; i < n; ++i)
    for (int j = i; j < n; ++j) {
      double s = 0;
      for (int k = 0; k < n; ++k) s += logs[static_cast<size_t>(k)] * vectors.at<double>(k, i) * vectors.at<double>(k, j);
      out.push_back(i == j ? s + shift : std::sqrt(2.0) * s);
    }
}

}  // namespace

void GogOptions::check() const {
  if (patch < 2 || stride < 1) throw OptionError("GogOptions", "patch", "must be >= 2, and stride >= 1");
  if (width < patch || height < 8) throw OptionError("GogOptions", "width", "and height must be at least one patch and 8 rows");
  if (regions < 1) throw OptionError("GogOptions", "regions", "must be >= 1");
  if (!(epsilon > 0)) throw OptionError("GogOptions", "epsilon", "must be > 0");
}

int gog_length(GogColour colour, const GogOptions& o) {
  const int d = pixel_features(colour), m = triangle(d + 1);
  return o.regions * triangle(m + 1);
}

std::vector<float> gog_features(const PersonImage& image, GogColour colour, const GogOptions& o) {
  CV_Assert(!image.bgr.empty() && image.bgr.type() == CV_8UC3);
  CV_Assert(image.mask.empty() || (image.mask.type() == CV_8U && image.mask.size() == image.bgr.size()));
  const cv::Size size(o.width, o.height);
  const cv::Mat bgr = resample_image(image.bgr, size);
  const cv::Mat mask = image.mask.empty() ? cv::Mat() : resample_mask(image.mask, size);
  const int d = pixel_features(colour), m = triangle(d + 1);
  static_assert(kMaxPixelFeatures >= 8, "pixel features fit");
  const cv::Mat pixels = pixel_feature_image(bgr, colour);

  // Patch vectors, with their centres and body fractions.
  const int rows = (o.height - o.patch) / o.stride + 1, cols = (o.width - o.patch) / o.stride + 1;
  const int area = o.patch * o.patch;
  cv::Mat patches(rows * cols, m, CV_64F);
  std::vector<double> centre_x, centre_y, body;
  std::vector<double> values;
  values.reserve(static_cast<size_t>(m));
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      std::vector<double> mu(static_cast<size_t>(d), 0.0), cov(static_cast<size_t>(d * d), 0.0);
      int inside = 0;
      for (int y = r * o.stride; y < r * o.stride + o.patch; ++y)
        for (int x = c * o.stride; x < c * o.stride + o.patch; ++x) {
          const double* v = pixels.ptr<double>(y * o.width + x);
          inside += mask.empty() || mask.at<uchar>(y, x) != 0;
          for (int i = 0; i < d; ++i) {
            mu[static_cast<size_t>(i)] += v[i];
            for (int j = i; j < d; ++j) cov[static_cast<size_t>(i * d + j)] += v[i] * v[j];
          }
        }
      for (double& v : mu) v /= area;
      for (int i = 0; i < d; ++i)
        for (int j = i; j < d; ++j)
          cov[static_cast<size_t>(i * d + j)] = cov[static_cast<size_t>(j * d + i)] =
              cov[static_cast<size_t>(i * d + j)] / area - mu[static_cast<size_t>(i)] * mu[static_cast<size_t>(j)];
      values.clear();
      append_log_gaussian(mu, cov, o.epsilon, values);
      const int index = r * cols + c;
      std::copy(values.begin(), values.end(), patches.ptr<double>(index));
      centre_x.push_back(c * o.stride + o.patch / 2.0);
      centre_y.push_back(r * o.stride + o.patch / 2.0);
      body.push_back(double(inside) / area);
    }

  // Region Gaussians of the patch vectors.
  std::vector<float> out;
  out.reserve(static_cast<size_t>(gog_length(colour, o)));
  const double sigma = o.width / 4.0, region_height = o.height / 4.0, step = o.height / 8.0;
  for (int g = 0; g < o.regions; ++g) {
    const double top = g * step, bottom = top + region_height;
    cv::Mat mu = cv::Mat::zeros(m, 1, CV_64F), second = cv::Mat::zeros(m, m, CV_64F);
    double total = 0;
    // Weighted first and second moments, accumulated in place: a matrix expression per patch would allocate
    // three matrices each time, most of the descriptor's time. Both triangles are summed, as (w z_a) z_b, so
    // the result is bit for bit that of the expression (and the models trained on it stay the same).
    std::vector<double> wz(static_cast<size_t>(m));
    double* mu_p = mu.ptr<double>();
    for (int i = 0; i < patches.rows; ++i) {
      if (centre_y[i] < top || centre_y[i] >= bottom || body[i] < 0.5) continue;
      const double dx = centre_x[i] - o.width / 2.0, w = std::exp(-dx * dx / (2 * sigma * sigma));
      const double* z = patches.ptr<double>(i);
      for (int a = 0; a < m; ++a) wz[static_cast<size_t>(a)] = w * z[a], mu_p[a] += wz[static_cast<size_t>(a)];
      for (int a = 0; a < m; ++a) {
        double* row = second.ptr<double>(a);
        for (int b = 0; b < m; ++b) row[b] += wz[static_cast<size_t>(a)] * z[b];
      }
      total += w;
    }
    if (total <= 0) {
      out.resize(out.size() + static_cast<size_t>(triangle(m + 1)), 0.0f);
      continue;
    }
    mu /= total;
    const cv::Mat cov = second / total - mu * mu.t();
    values.clear();
    append_log_gaussian(std::vector<double>(mu.begin<double>(), mu.end<double>()),
                        std::vector<double>(cov.begin<double>(), cov.end<double>()), o.epsilon, values);
    for (double v : values) out.push_back(static_cast<float>(v));
  }
  return out;
}

}  // namespace bodyrec
