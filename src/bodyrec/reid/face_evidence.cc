#include "bodyrec/reid/face_evidence.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <tuple>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {

std::string default_face_cascade() {
  return "/usr/share/opencv4/haarcascades/haarcascade_frontalface_alt2.xml";
}

cv::Rect largest_face(const std::vector<cv::Rect>& faces) {
  CV_Assert(!faces.empty());
  return *std::min_element(faces.begin(), faces.end(), [](const cv::Rect& a, const cv::Rect& b) {
    return std::make_tuple(-a.area(), a.y, a.x, a.width) < std::make_tuple(-b.area(), b.y, b.x, b.width);
  });
}

FaceDetector::FaceDetector(const std::string& cascade_file) {
  const std::string file = cascade_file.empty() ? default_face_cascade() : cascade_file;
  if (!std::filesystem::exists(file))
    throw InputError(file + ": face cascade not found (Debian package opencv-data, scripts/install-deps)");
  if (!cascade_.load(file)) throw InputError(file + ": cannot load the face cascade");
}

FaceResult FaceDetector::detect(const cv::Mat& color, const cv::Rect2d& head, int min_head_px) {
  FaceResult r;
  if (color.empty() || head.height < min_head_px || head.width < 4) return r;
  // Search a margin around the expected head: joints and masks are a few centimetres off.
  const double m = 0.35 * head.height;
  const cv::Rect2d wide(head.x - m, head.y - m, head.width + 2 * m, head.height + 2 * m);
  const cv::Rect roi = cv::Rect(cv::Rect2d(std::floor(wide.x), std::floor(wide.y), std::ceil(wide.width),
                                           std::ceil(wide.height))) &
                       cv::Rect(0, 0, color.cols, color.rows);
  if (roi.area() < 0.5 * wide.area()) return r;
  r.looked = true;
  cv::cvtColor(color(roi), grey_, cv::COLOR_BGR2GRAY);
  const double scale = std::clamp(64.0 / head.height, 0.5, 4.0);
  if (std::abs(scale - 1) > 0.05) cv::resize(grey_, grey_, cv::Size(), scale, scale, cv::INTER_LINEAR);
  cv::equalizeHist(grey_, grey_);
  std::vector<cv::Rect> faces;
  const int min_face = std::max(16, static_cast<int>(0.45 * head.height * scale));
  const int max_face = std::max(min_face + 1, static_cast<int>(1.6 * head.height * scale));
  cascade_.detectMultiScale(grey_, faces, 1.1, 3, 0, cv::Size(min_face, min_face), cv::Size(max_face, max_face));
  if (faces.empty()) return r;
  const cv::Rect best = largest_face(faces);
  r.face = true;
  r.box = cv::Rect(roi.x + static_cast<int>(best.x / scale), roi.y + static_cast<int>(best.y / scale),
                   static_cast<int>(best.width / scale), static_cast<int>(best.height / scale));
  return r;
}

}  // namespace bodyrec
