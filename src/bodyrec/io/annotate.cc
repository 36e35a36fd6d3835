#include "bodyrec/io/annotate.h"

#include <opencv2/imgproc.hpp>

namespace bodyrec {

cv::Scalar role_color(Role role) {
  switch (role) {
    case Role::kLeader: return colors::kBlue;
    case Role::kMember: return colors::kGreen;
    case Role::kNonMember: return colors::kRed;
    case Role::kPotentialMember: return colors::kOrange;
    case Role::kUnknown: break;
  }
  return colors::kWhite;
}

cv::Scalar id_color(int id) {
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar((id * 137) % 180, 220, 255)), bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const auto c = bgr.at<cv::Vec3b>(0, 0);
  return cv::Scalar(c[0], c[1], c[2]);
}

void draw_labelled_box(cv::Mat& image, const Box& box, const cv::Scalar& color, const std::string& label,
                       int thickness) {
  const cv::Rect r(cvRound(box.x), cvRound(box.y), cvRound(box.width), cvRound(box.height));
  cv::rectangle(image, r, color, thickness, cv::LINE_AA);
  if (label.empty()) return;
  int baseline = 0;
  const double scale = 0.4;
  const cv::Size t = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &baseline);
  const cv::Point origin(r.x, std::max(t.height + 2, r.y - 2));
  cv::rectangle(image, cv::Rect(origin.x, origin.y - t.height - 2, t.width + 4, t.height + 4), color, cv::FILLED);
  const double luma = 0.114 * color[0] + 0.587 * color[1] + 0.299 * color[2];
  cv::putText(image, label, origin + cv::Point(2, 0), cv::FONT_HERSHEY_SIMPLEX, scale,
              luma > 128 ? colors::kBlack : colors::kWhite, 1, cv::LINE_AA);
}

void draw_caption(cv::Mat& image, const std::string& text) {
  int baseline = 0;
  const cv::Size t = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, 0.5, 1, &baseline);
  cv::rectangle(image, cv::Rect(0, 0, t.width + 12, t.height + 12), cv::Scalar(0, 0, 0), cv::FILLED);
  cv::putText(image, text, cv::Point(6, t.height + 5), cv::FONT_HERSHEY_SIMPLEX, 0.5, colors::kWhite, 1,
              cv::LINE_AA);
}

}  // namespace bodyrec
