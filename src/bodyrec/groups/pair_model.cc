#include "bodyrec/groups/pair_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <opencv2/core.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/core/parse_number.h"

namespace bodyrec {
namespace {

constexpr const char* kHeader = "bodyrec-pair-model 1";

std::string numbers(const double* v, int n) {
  std::string s;
  char buffer[32];
  for (int i = 0; i < n; ++i) {
    std::snprintf(buffer, sizeof buffer, " %.9g", v[i]);
    s += buffer;
  }
  return s;
}

std::vector<double> parse_numbers(std::istringstream& s, const std::string& where) {
  std::vector<double> v;
  for (std::string field; s >> field;) {
    const auto x = parse_double(field);
    if (!x || !std::isfinite(*x)) throw InputError(where + ": not a finite number: '" + field + "'");
    v.push_back(*x);
  }
  return v;
}

void copy_exact(const std::vector<double>& v, double* out, size_t n, const std::string& where) {
  if (v.size() != n)
    throw InputError(where + ": expected " + std::to_string(n) + " numbers, got " + std::to_string(v.size()));
  std::copy(v.begin(), v.end(), out);
}

}  // namespace

double PairModel::logit(const PairFeatureVector& x) const {
  double z = bias;
  for (int i = 0; i < kPairFeatureCount; ++i) z += weights[i] * (x[i] - mean[i]) / scale[i];
  return z;
}

bool PairModel::trained_on_scene(const std::string& scene) const {
  return std::find(trained_on.begin(), trained_on.end(), scene) != trained_on.end();
}

std::string to_text(const PairModel& m) {
  std::string s = std::string(kHeader) + "\ntrained_on";
  for (const auto& name : m.trained_on) s += " " + name;
  s += "\nwindow_s" + numbers(&m.window_s, 1) + "\nvelocity_span_s" + numbers(&m.velocity_span_s, 1);
  s += "\nl2" + numbers(&m.l2, 1);
  s += "\nmean" + numbers(m.mean.data(), kPairFeatureCount);
  s += "\nscale" + numbers(m.scale.data(), kPairFeatureCount);
  s += "\nweights" + numbers(m.weights.data(), kPairFeatureCount);
  s += "\nbias" + numbers(&m.bias, 1) + "\n";
  return s;
}

PairModel parse_pair_model(const std::string& text, const std::string& where) {
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != kHeader)
    throw InputError(where + ":1: not a bodyrec pair model (expected '" + kHeader + "')");
  PairModel m;
  std::map<std::string, bool> seen;
  for (int number = 2; std::getline(in, line); ++number) {
    std::istringstream s(line);
    std::string key;
    if (!(s >> key)) continue;
    const std::string at = where + ":" + std::to_string(number) + ": " + key;
    if (seen[key]) throw InputError(at + ": given twice");
    seen[key] = true;
    if (key == "trained_on") {
      for (std::string name; s >> name;) m.trained_on.push_back(name);
      continue;
    }
    const std::vector<double> v = parse_numbers(s, at);
    if (key == "window_s") copy_exact(v, &m.window_s, 1, at);
    else if (key == "velocity_span_s") copy_exact(v, &m.velocity_span_s, 1, at);
    else if (key == "l2") copy_exact(v, &m.l2, 1, at);
    else if (key == "mean") copy_exact(v, m.mean.data(), kPairFeatureCount, at);
    else if (key == "scale") copy_exact(v, m.scale.data(), kPairFeatureCount, at);
    else if (key == "weights") copy_exact(v, m.weights.data(), kPairFeatureCount, at);
    else if (key == "bias") copy_exact(v, &m.bias, 1, at);
    else throw InputError(at + ": unknown key");
  }
  for (const char* key : {"trained_on", "window_s", "velocity_span_s", "l2", "mean", "scale", "weights", "bias"})
    if (!seen[key]) throw InputError(where + ": missing '" + key + "'");
  for (int i = 0; i < kPairFeatureCount; ++i)
    if (!(m.scale[i] > 0)) throw InputError(where + ": scale of feature " + std::to_string(i) + " is not > 0");
  if (!(m.window_s > 0)) throw InputError(where + ": window_s is not > 0");
  return m;
}

PairModel read_pair_model(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path + ": no such file");
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw InputError(path + ": cannot read");
  return parse_pair_model(text.str(), path);
}

PairModel train_pair_model(const std::vector<PairExample>& examples, double l2) {
  constexpr int k = kPairFeatureCount;
  PairModel m;
  double total = 0, positive = 0;
  for (const auto& e : examples) {
    total += e.weight;
    if (e.together) positive += e.weight;
    for (int i = 0; i < k; ++i) m.mean[i] += e.weight * e.x[i];
  }
  if (!(positive > 0) || !(positive < total))
    throw ProcessingError("pair model training needs examples of pairs together and apart");
  for (int i = 0; i < k; ++i) m.mean[i] /= total;
  for (const auto& e : examples)
    for (int i = 0; i < k; ++i) m.scale[i] += e.weight * (e.x[i] - m.mean[i]) * (e.x[i] - m.mean[i]);
  for (int i = 0; i < k; ++i) m.scale[i] = std::max(1e-6, std::sqrt(m.scale[i] / total));

  // Newton iterations on the weighted mean log-likelihood (example weights normalised to sum to 1, so l2
  // does not depend on how many examples there are).
  cv::Mat beta = cv::Mat::zeros(k + 1, 1, CV_64F);  // bias last
  std::vector<std::array<double, k + 1>> z(examples.size());
  for (size_t n = 0; n < examples.size(); ++n) {
    for (int i = 0; i < k; ++i) z[n][i] = (examples[n].x[i] - m.mean[i]) / m.scale[i];
    z[n][k] = 1;
  }
  for (int iteration = 0; iteration < 50; ++iteration) {
    cv::Mat hessian = cv::Mat::zeros(k + 1, k + 1, CV_64F), gradient = cv::Mat::zeros(k + 1, 1, CV_64F);
    for (size_t n = 0; n < examples.size(); ++n) {
      double s = 0;
      for (int i = 0; i <= k; ++i) s += beta.at<double>(i) * z[n][i];
      const double p = 1 / (1 + std::exp(-s));
      const double w = examples[n].weight / total;
      const double r = w * ((examples[n].together ? 1.0 : 0.0) - p), c = w * p * (1 - p);
      for (int i = 0; i <= k; ++i) {
        gradient.at<double>(i) += r * z[n][i];
        for (int j = 0; j <= i; ++j) hessian.at<double>(i, j) += c * z[n][i] * z[n][j];
      }
    }
    for (int i = 0; i <= k; ++i)
      for (int j = 0; j < i; ++j) hessian.at<double>(j, i) = hessian.at<double>(i, j);
    for (int i = 0; i < k; ++i) {
      hessian.at<double>(i, i) += l2;
      gradient.at<double>(i) -= l2 * beta.at<double>(i);
    }
    cv::Mat step;
    cv::solve(hessian, gradient, step, cv::DECOMP_CHOLESKY);
    beta += step;
    if (cv::norm(step, cv::NORM_INF) < 1e-10) break;
  }
  for (int i = 0; i < k; ++i) m.weights[i] = beta.at<double>(i);
  m.bias = beta.at<double>(k);
  m.l2 = l2;
  return m;
}

const PairModel& builtin_pair_model_for(const std::string& scene) {
  const auto& models = builtin_pair_models();
  if (models.empty()) throw ProcessingError("this build has no built-in pair model");
  const PairModel* best = nullptr;
  for (const auto& m : models)
    if (!m.trained_on_scene(scene) && (!best || m.trained_on.size() > best->trained_on.size())) best = &m;
  bool known = false;
  for (const auto& m : models) known = known || m.trained_on_scene(scene);
  if (!known || !best) {  // a new scene: the model trained on the most data
    best = &models.front();
    for (const auto& m : models)
      if (m.trained_on.size() > best->trained_on.size()) best = &m;
  }
  return *best;
}

}  // namespace bodyrec
