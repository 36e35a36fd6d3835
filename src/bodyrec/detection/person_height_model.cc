#include "bodyrec/detection/person_height_model.h"

#include <algorithm>
#include <cmath>

namespace bodyrec {

PersonHeightModel::PersonHeightModel(int min_samples, int capacity)
    : min_samples_(std::max(2, min_samples)), capacity_(std::max(min_samples_, capacity)) {}

void PersonHeightModel::add(double foot_y, double height) {
  if (!std::isfinite(foot_y) || !(height > 0)) return;
  samples_.emplace_back(foot_y, height);
  while (static_cast<int>(samples_.size()) > capacity_) samples_.pop_front();
  // Refit every 10 samples: the line moves slowly and the fit is O(n).
  if (++added_since_fit_ >= 10 || (!valid_ && static_cast<int>(samples_.size()) >= min_samples_)) refit();
}

void PersonHeightModel::refit() {
  added_since_fit_ = 0;
  valid_ = false;
  const double n = static_cast<double>(samples_.size());
  if (static_cast<int>(samples_.size()) < min_samples_) return;
  double sy = 0, sh = 0, syy = 0, syh = 0;
  for (const auto& [y, h] : samples_) {
    sy += y;
    sh += h;
    syy += y * y;
    syh += y * h;
  }
  const double var = syy - sy * sy / n;
  slope_ = var > 1e-9 ? (syh - sy * sh / n) / var : 0.0;
  intercept_ = (sh - slope_ * sy) / n;
  double rel = 0;
  for (const auto& [y, h] : samples_) {
    const double e = (h - (slope_ * y + intercept_)) / h;
    rel += e * e;
  }
  valid_ = std::sqrt(rel / n) <= 0.25;
}

std::optional<double> PersonHeightModel::height_at(double foot_y) const {
  if (!valid_) return std::nullopt;
  const double h = slope_ * foot_y + intercept_;
  if (!(h > 0)) return std::nullopt;
  return h;
}

std::optional<std::pair<double, double>> PersonHeightModel::height_range(double y0, double y1, double margin) const {
  const auto a = height_at(y0), b = height_at(y1);
  if (!a || !b) return std::nullopt;
  return std::make_pair(std::min(*a, *b) * (1 - margin), std::max(*a, *b) * (1 + margin));
}

}  // namespace bodyrec
