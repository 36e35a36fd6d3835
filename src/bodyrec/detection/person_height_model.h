// How tall people look at each image row, learned from a fixed camera's own detections: on a flat floor
// seen in perspective, a person's height in pixels is close to a straight line in the row of their feet.
// The HOG detector uses it to search each region only at the scales people can have there.
#pragma once

#include <deque>
#include <optional>
#include <utility>

namespace bodyrec {

class PersonHeightModel {
 public:
  // `min_samples`: detections before the model is used; `capacity`: the most recent ones kept.
  explicit PersonHeightModel(int min_samples = 40, int capacity = 400);

  void add(double foot_y, double height);

  // Expected height (pixels) for a person whose feet are on row `foot_y`; nullopt until min_samples
  // detections were added, or when the fit is poor (relative residual std-dev above 0.25: not one floor).
  std::optional<double> height_at(double foot_y) const;

  // [lowest, highest] expected height for feet anywhere on rows [y0, y1], widened by `margin` (0.35 =
  // 35 % either way); nullopt as for height_at.
  std::optional<std::pair<double, double>> height_range(double y0, double y1, double margin) const;

 private:
  void refit();

  int min_samples_, capacity_;
  std::deque<std::pair<double, double>> samples_;  // (foot y, height)
  bool valid_ = false;
  double slope_ = 0, intercept_ = 0;
  int added_since_fit_ = 0;
};

}  // namespace bodyrec
