// The 180 body-contour landmarks of every person in a photo (thesis Ch3): find the people, then fit the
// shipped body shape model in each box.
//
//   landmarks_on_image photo.jpg
#include <cstdio>

#include <opencv2/imgcodecs.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/core/model_files.h"
#include "bodyrec/detection/dpm_people_detector.h"
#include "bodyrec/landmarks/body_shape.h"

int main(int argc, char** argv) try {
  if (argc < 2) {
    std::fprintf(stderr, "usage: landmarks_on_image IMAGE\n");
    return 2;
  }
  const cv::Mat image = cv::imread(argv[1], cv::IMREAD_COLOR);
  if (image.empty()) throw bodyrec::InputError(std::string(argv[1]) + ": cannot read the image");

  // The shipped model, found next to the installed library (models/README.md says how it was made).
  const bodyrec::BodyShapeModel shape(
      bodyrec::require_model_file(bodyrec::kShippedShapeModel, "reinstall bodyrec, or train one with bodyrec train-shape"));
  // People of any size in a still photo: OpenCV's DPM with the INRIA person model (Debian's opencv-doc).
  bodyrec::DpmPeopleDetector detector(bodyrec::dpm_photo_preset());

  const cv::Mat prepared = shape.prepare(image);
  const std::vector<bodyrec::Detection> people = detector.detect(image);
  for (const bodyrec::Detection& d : people) {
    const std::vector<cv::Point2d> points = shape.fit(prepared, d.box);
    std::printf("person at (%.0f, %.0f, %.0f x %.0f): %zu landmarks, the first at (%.1f, %.1f)\n", d.box.x, d.box.y,
                d.box.width, d.box.height, points.size(), points.empty() ? 0.0 : points[0].x,
                points.empty() ? 0.0 : points[0].y);
  }
  std::printf("%zu people\n", people.size());
  return 0;
} catch (const bodyrec::Error& e) {
  std::fprintf(stderr, "landmarks_on_image: %s\n", e.what());
  return static_cast<int>(e.code());
}
