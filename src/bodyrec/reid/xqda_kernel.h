// Internal to the XQDA files (xqda.cc, xqda_ensemble.cc, xqda_selection.cc): models trained on subsets
// of one training set through its Gram matrix, and their distances on the other samples.
#pragma once

#include <utility>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/reid/xqda.h"

namespace bodyrec::xqda_detail {

// The threshold with the lowest balanced error (mean of false-accept and false-reject rates) over
// (distance, same person) pairs; 0 when one kind is missing.
double balanced_threshold(std::vector<std::pair<double, bool>> pairs);

// gram(rows, cols) as a new CV_64F matrix.
cv::Mat sub_gram(const cv::Mat& gram, const std::vector<int>& rows, const std::vector<int>& cols);

// Embeddings (one row per sample of `others`) under `fit`, trained on the samples `fit_rows` of `gram`.
cv::Mat embed_others(const cv::Mat& gram, const std::vector<int>& fit_rows, const XqdaFit& fit,
                     const std::vector<int>& others);

// Squared Euclidean distances between the rows of a and of b (CV_64F a.rows x b.rows).
cv::Mat row_distances(const cv::Mat& a, const cv::Mat& b);

// Median of the entries of `distances` whose pair is not the same person (0 when there is none).
double different_person_median(const std::vector<std::pair<double, bool>>& pairs);

}  // namespace bodyrec::xqda_detail
