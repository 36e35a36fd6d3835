#include "bodyrec/detection/fhog_detector.h"

#include <fstream>
#include <sstream>

#include <dlib/image_processing.h>
#include <dlib/opencv/cv_image.h>
#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {

struct FhogDetector::Model {
  dlib::object_detector<dlib::scan_fhog_pyramid<dlib::pyramid_down<6>>> detector;
};

void FhogOptions::check() const {
  const auto fail = [](const char* field, const char* problem) { throw OptionError("FhogOptions", field, problem); };
  if (model_path.empty()) fail("model_path", "is required (a dlib fHOG .svm file)");
  if (!(upsample > 0.05 && upsample <= 8)) fail("upsample", "must be in (0.05, 8]");
  if (!(nms_iou > 0 && nms_iou <= 1)) fail("nms_iou", "must be in (0, 1]");
}

FhogDetector::FhogDetector(const FhogOptions& options) : options_(options), model_(std::make_unique<Model>()) {
  options_.check();
  std::ifstream in(options_.model_path, std::ios::binary);
  if (!in) throw InputError("cannot read detector model " + options_.model_path);
  try {
    dlib::deserialize(model_->detector, in);
  } catch (const std::exception& e) {
    std::string why = e.what();
    why = why.substr(0, why.find('\n'));
    throw InputError(options_.model_path + ": not a dlib fHOG object detector (" + why + ")");
  }
  if (model_->detector.num_detectors() == 0)
    throw InputError(options_.model_path + ": detector file holds no detector");
}

FhogDetector::~FhogDetector() = default;

cv::Size FhogDetector::window_size() const {
  const auto& scanner = model_->detector.get_scanner();
  return cv::Size(static_cast<int>(scanner.get_detection_window_width()),
                  static_cast<int>(scanner.get_detection_window_height()));
}

std::vector<Detection> FhogDetector::detect(const cv::Mat& frame) {
  cv::Mat image;
  const double f = options_.upsample;
  if (f != 1.0) cv::resize(frame, image, cv::Size(), f, f, f > 1 ? cv::INTER_LINEAR : cv::INTER_AREA);
  else image = frame;
  dlib::cv_image<dlib::bgr_pixel> view(image);
  std::vector<dlib::rect_detection> found;
  model_->detector(view, found, options_.adjust_threshold);
  std::vector<Detection> out;
  for (const auto& d : found) {
    const dlib::rectangle& r = d.rect;
    const Box b = scale_box(Box(r.left(), r.top(), r.width(), r.height()), 1.0 / f);
    const Box clipped = clip_box(b, frame.size());
    if (clipped.area() > 0) out.push_back({clipped, d.detection_confidence});
  }
  return finalize_detections(non_max_suppression(std::move(out), options_.nms_iou));
}

std::string FhogDetector::describe() const {
  std::ostringstream s;
  const cv::Size w = window_size();
  s << "dlib fHOG (" << options_.model_path << ", window " << w.width << "x" << w.height << ", upsample "
    << options_.upsample << ")";
  return s.str();
}

}  // namespace bodyrec
