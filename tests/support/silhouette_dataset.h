// Landmark datasets of drawn people (synthetic_silhouette.h): boxes and landmarks from each mask's outline.
#pragma once

#include <string>

#include "bodyrec/landmarks/contour.h"
#include "bodyrec/landmarks/landmark_dataset.h"
#include "synthetic_silhouette.h"

namespace bodyrec::testing {

// `count` images of `size`, each with one drawn person of `height` px (seeds first_seed, first_seed + 1, ...)
// whose box and `landmarks` landmarks come from its mask's outline; image paths are `name` + index.
inline LandmarkDataset silhouette_dataset(int count, uint64_t first_seed, int landmarks, cv::Size size, int height,
                                          const std::string& name) {
  LandmarkDataset data;
  data.landmarks = landmarks;
  ContourOptions o;
  o.landmarks = landmarks;
  for (int i = 0; i < count; ++i) {
    const Silhouette s = make_silhouette(size, height, first_seed + static_cast<uint64_t>(i));
    const BodyContour c = contour_from_mask(s.mask, o);
    EXPECT_EQ(c.status, ContourStatus::kOk);
    AnnotatedImage image;
    image.path = name + std::to_string(i);
    image.image = s.image;
    image.people.push_back({Box(c.bounds), c.points, false});
    data.images.push_back(std::move(image));
  }
  return data;
}

}  // namespace bodyrec::testing
