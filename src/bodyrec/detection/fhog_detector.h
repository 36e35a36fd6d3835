// A dlib fHOG + linear SVM sliding-window detector loaded from a `.svm` file written by dlib's
// serialize() (object_detector<scan_fhog_pyramid<pyramid_down<6>>>), e.g. by `bodyrec train-detector`,
// dlib's imglab/train_object_detector, or the thesis author's ../shared/datasets/thesis_ch3 release.
#pragma once

#include <memory>
#include <string>

#include "bodyrec/detection/people_detector.h"

namespace bodyrec {

struct FhogOptions {
  std::string model_path;
  double adjust_threshold = 0.0;  // added to the detector's own threshold (negative finds more)
  double upsample = 1.0;          // image scale factor before detection (2 finds people half the size)
  double nms_iou = 0.4;
  void check() const;
};

class FhogDetector : public PeopleDetector {
 public:
  // Throws InputError naming the file when it is missing or not a dlib fHOG object detector.
  explicit FhogDetector(const FhogOptions& options);
  ~FhogDetector() override;
  std::vector<Detection> detect(const cv::Mat& frame) override;
  std::string describe() const override;
  // The sliding window size the model was trained with (width x height, pixels).
  cv::Size window_size() const;

 private:
  struct Model;
  FhogOptions options_;
  std::unique_ptr<Model> model_;
};

}  // namespace bodyrec
