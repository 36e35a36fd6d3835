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

// `infinite_ok`: "inf" is accepted too (window_s: the whole common time).
std::vector<double> parse_numbers(std::istringstream& s, const std::string& where, bool infinite_ok = false) {
  std::vector<double> v;
  for (std::string field; s >> field;) {
    const auto x = parse_double(field);
    const bool ok = x && (std::isfinite(*x) || (infinite_ok && field == "inf"));
    if (!ok) throw InputError(where + ": not a finite number: '" + field + "'");
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

const char* to_string(GroupLinkage linkage) {
  switch (linkage) {
    case GroupLinkage::kNone: return "none";
    case GroupLinkage::kSingle: return "single";
    case GroupLinkage::kAverage: return "average";
  }
  return "?";
}

double PairModel::logit(const PairFeatureVector& x) const {
  if (rule) {  // features 0 and 4: log(median distance + 0.1), median speed difference
    const bool together = x[0] <= std::log(max_distance_m + 0.1) && x[4] <= max_speed_difference;
    return bias + weights[0] * (together ? 1.0 : -1.0);
  }
  double z = bias;
  for (int i = 0; i < kPairFeatureCount; ++i) z += weights[i] * (x[i] - mean[i]) / scale[i];
  return z;
}

std::string describe(const PairModel& m) {
  char buffer[256];
  std::string window = "over the whole common time";
  if (!std::isinf(m.window_s)) {
    std::snprintf(buffer, sizeof buffer, "over %g s windows", m.window_s);
    window = buffer;
  }
  if (m.rule)
    std::snprintf(buffer, sizeof buffer, "learned rule: median distance <= %g m and median speed difference <= %g m/s",
                  m.max_distance_m, m.max_speed_difference);
  else
    std::snprintf(buffer, sizeof buffer, "logistic regression on %zu features", m.features.count());
  std::string s = std::string(buffer) + " " + window;
  std::snprintf(buffer, sizeof buffer, ", min-moving %g, linkage %s", m.min_moving_fraction, to_string(m.linkage));
  return s + buffer;
}

bool PairModel::trained_on_scene(const std::string& scene) const {
  return std::find(trained_on.begin(), trained_on.end(), scene) != trained_on.end();
}

std::string to_text(const PairModel& m) {
  std::string s = std::string(kHeader) + "\ntrained_on";
  for (const auto& name : m.trained_on) s += " " + name;
  s += "\nwindow_s" + numbers(&m.window_s, 1) + "\nvelocity_span_s" + numbers(&m.velocity_span_s, 1);
  s += "\nl2" + numbers(&m.l2, 1) + "\nfeatures";
  for (int i = 0; i < kPairFeatureCount; ++i)
    if (m.features[i]) s += std::string(" ") + kPairFeatureNames[i];
  s += "\nmin_moving" + numbers(&m.min_moving_fraction, 1) + "\nlinkage " + to_string(m.linkage);
  if (m.rule) s += "\nrule" + numbers(&m.max_distance_m, 1) + numbers(&m.max_speed_difference, 1);
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
    if (key == "features") {
      m.features.reset();
      for (std::string name; s >> name;) {
        const auto it = std::find(kPairFeatureNames.begin(), kPairFeatureNames.end(), name);
        if (it == kPairFeatureNames.end()) throw InputError(at + ": unknown feature '" + name + "'");
        m.features.set(static_cast<size_t>(it - kPairFeatureNames.begin()));
      }
      if (m.features.none()) throw InputError(at + ": no feature named");
      continue;
    }
    if (key == "linkage") {
      std::string name, extra;
      s >> name;
      if (name == "none") m.linkage = GroupLinkage::kNone;
      else if (name == "single") m.linkage = GroupLinkage::kSingle;
      else if (name == "average") m.linkage = GroupLinkage::kAverage;
      else throw InputError(at + ": expected none, single or average, got '" + name + "'");
      if (s >> extra) throw InputError(at + ": expected one value");
      continue;
    }
    const std::vector<double> v = parse_numbers(s, at, key == "window_s");
    if (key == "window_s") copy_exact(v, &m.window_s, 1, at);
    else if (key == "velocity_span_s") copy_exact(v, &m.velocity_span_s, 1, at);
    else if (key == "l2") copy_exact(v, &m.l2, 1, at);
    else if (key == "min_moving") copy_exact(v, &m.min_moving_fraction, 1, at);
    else if (key == "rule") {
      double limits[2];
      copy_exact(v, limits, 2, at);
      if (!(limits[0] > 0) || !(limits[1] >= 0))
        throw InputError(at + ": expected a max distance > 0 and a max speed difference >= 0");
      m.rule = true;
      m.max_distance_m = limits[0];
      m.max_speed_difference = limits[1];
    }
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
  if (!(m.velocity_span_s > 0)) throw InputError(where + ": velocity_span_s is not > 0");
  if (!(m.min_moving_fraction >= 0 && m.min_moving_fraction <= 1))
    throw InputError(where + ": min_moving is not in [0, 1]");
  for (int i = 0; i < kPairFeatureCount; ++i)
    if (!m.features[i] && m.weights[i] != 0)
      throw InputError(where + ": feature " + kPairFeatureNames[i] + " is not used but has a weight");
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

PairModel train_pair_model(const std::vector<PairExample>& examples, double l2, PairFeatureSet features) {
  constexpr int k = kPairFeatureCount;
  if (features.none()) throw UsageError("pair model training needs at least one feature");
  PairModel m;
  m.features = features;
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
  // does not depend on how many examples there are), over the used features only.
  std::vector<int> used;
  for (int i = 0; i < k; ++i)
    if (features[i]) used.push_back(i);
  const int u = static_cast<int>(used.size());
  cv::Mat beta = cv::Mat::zeros(u + 1, 1, CV_64F);  // bias last
  const size_t row = static_cast<size_t>(u) + 1;
  std::vector<double> z(examples.size() * row);  // standardised used features and 1, per example
  for (size_t n = 0; n < examples.size(); ++n) {
    for (int i = 0; i < u; ++i) z[n * row + i] = (examples[n].x[used[i]] - m.mean[used[i]]) / m.scale[used[i]];
    z[n * row + u] = 1;
  }
  for (int iteration = 0; iteration < 50; ++iteration) {
    cv::Mat hessian = cv::Mat::zeros(u + 1, u + 1, CV_64F), gradient = cv::Mat::zeros(u + 1, 1, CV_64F);
    for (size_t n = 0; n < examples.size(); ++n) {
      const double* zn = &z[n * row];
      double s = 0;
      for (int i = 0; i <= u; ++i) s += beta.at<double>(i) * zn[i];
      const double p = 1 / (1 + std::exp(-s));
      const double w = examples[n].weight / total;
      const double r = w * ((examples[n].together ? 1.0 : 0.0) - p), c = w * p * (1 - p);
      for (int i = 0; i <= u; ++i) {
        gradient.at<double>(i) += r * zn[i];
        for (int j = 0; j <= i; ++j) hessian.at<double>(i, j) += c * zn[i] * zn[j];
      }
    }
    for (int i = 0; i <= u; ++i)
      for (int j = 0; j < i; ++j) hessian.at<double>(j, i) = hessian.at<double>(i, j);
    for (int i = 0; i < u; ++i) {
      hessian.at<double>(i, i) += l2;
      gradient.at<double>(i) -= l2 * beta.at<double>(i);
    }
    cv::Mat step;
    cv::solve(hessian, gradient, step, cv::DECOMP_CHOLESKY);
    beta += step;
    if (cv::norm(step, cv::NORM_INF) < 1e-10) break;
  }
  for (int i = 0; i < u; ++i) m.weights[used[i]] = beta.at<double>(i);
  m.bias = beta.at<double>(u);
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
