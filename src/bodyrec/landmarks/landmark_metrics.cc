#include "bodyrec/landmarks/landmark_metrics.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "bodyrec/core/error.h"
#include "bodyrec/landmarks/contour.h"

namespace bodyrec {

PersonLandmarkError person_landmark_error(const std::vector<cv::Point2d>& predicted,
                                          const std::vector<cv::Point2d>& truth, const Box& box, int image_width) {
  CV_Assert(predicted.size() == truth.size() && !truth.empty());
  PersonLandmarkError e;
  for (size_t i = 0; i < truth.size(); ++i) {
    e.mean_px += cv::norm(predicted[i] - truth[i]);
    e.contour_px += distance_to_closed_polyline(predicted[i], truth);
  }
  e.mean_px /= static_cast<double>(truth.size());
  e.contour_px /= static_cast<double>(truth.size());
  e.box_height = std::max(1.0, box.height);
  e.image_width = std::max(1, image_width);
  return e;
}

double quantile(std::vector<double> values, double q) {
  CV_Assert(!values.empty());
  std::sort(values.begin(), values.end());
  const double rank = q * static_cast<double>(values.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(rank));
  const size_t hi = std::min(values.size() - 1, lo + 1);
  return values[lo] + (rank - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

LandmarkScores summarize_landmark_errors(const std::vector<PersonLandmarkError>& errors) {
  LandmarkScores s;
  s.persons = static_cast<int>(errors.size());
  if (errors.empty()) return s;
  std::vector<double> px, rel_height;
  for (const auto& e : errors) {
    px.push_back(e.mean_px);
    rel_height.push_back(e.mean_px / e.box_height);
    s.mean_px += e.mean_px;
    s.mean_rel_height += e.mean_px / e.box_height;
    s.mean_rel_width += e.mean_px / e.image_width;
    s.contour_px += e.contour_px;
    s.contour_rel_height += e.contour_px / e.box_height;
  }
  const double n = static_cast<double>(errors.size());
  s.mean_px /= n;
  s.mean_rel_height /= n;
  s.mean_rel_width /= n;
  s.contour_px /= n;
  s.contour_rel_height /= n;
  s.median_px = quantile(px, 0.5);
  s.p90_px = quantile(px, 0.9);
  s.median_rel_height = quantile(rel_height, 0.5);
  s.p90_rel_height = quantile(rel_height, 0.9);
  return s;
}

LandmarkScores evaluate_body_shape(const BodyShapeModel& model, const LandmarkDataset& data,
                                   const std::string& data_name, std::vector<PersonLandmarkError>* per_person) {
  if (data.landmarks != 0 && data.landmarks != model.landmarks())
    throw InputError(data_name + ": has " + std::to_string(data.landmarks) + " landmarks per box, the model " +
                     std::to_string(model.landmarks()));
  std::vector<PersonLandmarkError> errors;
  double fit_ms = 0;
  for (size_t i = 0; i < data.images.size(); ++i) {
    const auto& image = data.images[i];
    const cv::Mat prepared = model.prepare(image.image);
    for (const auto& person : image.people) {
      if (person.ignore || person.landmarks.empty()) continue;
      const auto t0 = std::chrono::steady_clock::now();
      const auto predicted = model.fit(prepared, person.box);
      fit_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      errors.push_back(person_landmark_error(predicted, person.landmarks, person.box, image.image.cols));
      errors.back().image = static_cast<int>(i);
    }
  }
  LandmarkScores s = summarize_landmark_errors(errors);
  s.ms_per_person = errors.empty() ? 0.0 : fit_ms / static_cast<double>(errors.size());
  if (per_person) *per_person = std::move(errors);
  return s;
}

}  // namespace bodyrec
