// Landmark accuracy: point-to-point error per person (the thesis's measure, in pixels and relative to the
// image width) plus relative to the box height, and point-to-contour error, which does not punish points
// that slide along the outline.
#pragma once

#include <vector>

#include <opencv2/core/types.hpp>

#include "bodyrec/core/geometry.h"
#include "bodyrec/landmarks/body_shape.h"
#include "bodyrec/landmarks/landmark_dataset.h"

namespace bodyrec {

struct PersonLandmarkError {
  double mean_px = 0;          // mean distance between predicted and true point i
  double contour_px = 0;       // mean distance from each predicted point to the true closed outline
  double box_height = 1;
  double image_width = 1;
  int image = -1;              // index into LandmarkDataset::images (set by evaluate_body_shape)
};

// REQUIRES: predicted.size() == truth.size() > 0.
PersonLandmarkError person_landmark_error(const std::vector<cv::Point2d>& predicted,
                                          const std::vector<cv::Point2d>& truth, const Box& box, int image_width);

struct LandmarkScores {
  int persons = 0;
  double mean_px = 0, median_px = 0, p90_px = 0;
  double mean_rel_height = 0, median_rel_height = 0, p90_rel_height = 0;  // error / box height
  double mean_rel_width = 0;                                                // error / image width
  double contour_px = 0, contour_rel_height = 0;                            // point-to-contour
  double ms_per_person = 0;                                                 // shape fitting time
};

// Aggregates per-person errors (median and 90th percentile by linear interpolation between ranks).
LandmarkScores summarize_landmark_errors(const std::vector<PersonLandmarkError>& errors);

// Fits `model` inside every non-ignored ground-truth box with landmarks and scores it (timing only the
// fitting). Throws InputError when the dataset's landmark count differs from the model's. When
// `per_person` is given it receives every person's error, in dataset order.
LandmarkScores evaluate_body_shape(const BodyShapeModel& model, const LandmarkDataset& data,
                                   const std::string& data_name,
                                   std::vector<PersonLandmarkError>* per_person = nullptr);

// The value at fraction q (0..1) of the sorted values, interpolating between ranks. REQUIRES: non-empty.
double quantile(std::vector<double> values, double q);

}  // namespace bodyrec
