// Training a dlib fHOG + linear SVM people detector (structural SVM), as the thesis did in Ch3, from boxes
// in an imglab dataset. The result loads with FhogDetector (`--model FILE.svm`).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "bodyrec/core/geometry.h"

namespace bodyrec {

// Options named as in the thesis's table (dlib's train_object_detector): defaults are dlib's; the
// thesis chose C 0.65, epsilon 0.01, target size 100, no upsampling, flip on.
struct FhogTrainOptions {
  double C = 1.0;            // SVM regularisation: larger fits the training set harder
  double epsilon = 0.01;     // stop when the risk gap is below this
  int target_size = 80;      // sliding window area = target_size^2, aspect ratio from the training boxes
  bool upsample = false;     // train on 2x upsampled images (detect with --fhog-upsample 2)
  bool flip = false;         // add left-right mirrored images
  int threads = 2;
  bool verbose = false;
  void check() const;        // throws UsageError
};

struct FhogTrainingImage {
  cv::Mat image;             // BGR
  std::vector<Box> boxes;    // people to find
  std::vector<Box> ignore;   // neither hits nor misses
};

struct FhogTrainReport {
  cv::Size window;           // sliding window (width x height)
  int boxes = 0;             // boxes trained on
  int unreachable = 0;       // boxes no window position/scale can match (dlib), moved to `ignore`
};

struct DetectionAccuracy {
  double precision = 0, recall = 0, average_precision = 0;
};

// Trains and writes the detector to `out_path` (dlib serialisation). Boxes the sliding window cannot
// match (dlib's remove_unobtainable_rectangles: too small, or of another shape) are ignored and counted. Throws
// ProcessingError when there is nothing to train on, dlib rejects the labels, or the file cannot be written.
FhogTrainReport train_fhog_detector(const std::vector<FhogTrainingImage>& images, const FhogTrainOptions& options,
                                    const std::string& out_path);

// Precision, recall (IoU >= 0.5, dlib's test_object_detection_function) and average precision of the
// detector in `model_path` on `images`, at `upsample` like training.
DetectionAccuracy test_fhog_detector(const std::string& model_path, const std::vector<FhogTrainingImage>& images,
                                     bool upsample);

}  // namespace bodyrec
