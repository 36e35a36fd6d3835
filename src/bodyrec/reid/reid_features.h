// The layout of the features online re-identification stores per scan: the matcher's descriptor, then
// kBodyFeatures floats of body measurements (stature in metres or NaN, and the number of frames it is the
// median of). Layout version 1 stored the matcher's descriptor alone.
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/reid/descriptor_view.h"
#include "bodyrec/store/gallery_types.h"

namespace bodyrec {

constexpr int kReidDescriptorVersion = 2;
constexpr int kBodyFeatures = 2;

// One row: the descriptor, the stature (NaN when unknown) and how many measurements it comes from.
cv::Mat reid_features(const std::vector<float>& descriptor, std::optional<double> stature, int count);
// The matcher's descriptor of a stored scan (without the body measurements), in place.
DescriptorView appearance_of(const GalleryEntry& entry);
// The stature stored with a scan, and how many measurements it comes from; none when unknown.
std::optional<double> stature_of(const GalleryEntry& entry);
float stature_count_of(const GalleryEntry& entry);

}  // namespace bodyrec
