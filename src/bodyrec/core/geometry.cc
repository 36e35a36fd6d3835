#include "bodyrec/core/geometry.h"

#include <algorithm>
#include <cmath>

namespace bodyrec {

double iou(const Box& a, const Box& b) {
  const double inter = (a & b).area();
  const double uni = a.area() + b.area() - inter;
  return (a.area() <= 0 || b.area() <= 0 || uni <= 0) ? 0.0 : inter / uni;
}

std::vector<Detection> non_max_suppression(std::vector<Detection> detections, double iou_threshold,
                                           double containment_threshold) {
  std::stable_sort(detections.begin(), detections.end(),
                   [](const Detection& a, const Detection& b) { return a.score > b.score; });
  std::vector<Detection> kept;
  for (const Detection& d : detections) {
    const bool suppressed = std::any_of(kept.begin(), kept.end(), [&](const Detection& k) {
      if (iou(d.box, k.box) > iou_threshold) return true;
      const double area = d.box.area();
      return area > 0 && (d.box & k.box).area() / area > containment_threshold;
    });
    if (!suppressed) kept.push_back(d);
  }
  return kept;
}

Box scale_box(const Box& b, double factor) {
  return Box(b.x * factor, b.y * factor, b.width * factor, b.height * factor);
}

Box round_box_for_output(const Box& b) {
  auto r = [](double v) { return std::round(v * 100) / 100; };
  return Box(r(b.x), r(b.y), r(b.width), r(b.height));
}

double round_score_for_output(double score) { return std::round(score * 1e6) / 1e6; }

Box clip_box(const Box& b, const cv::Size& size) {
  return b & Box(0, 0, size.width, size.height);
}

double box_gap(const Box& a, const Box& b) {
  const double dx = std::max({0.0, a.x - (b.x + b.width), b.x - (a.x + a.width)});
  const double dy = std::max({0.0, a.y - (b.y + b.height), b.y - (a.y + a.height)});
  return std::hypot(dx, dy);
}

}  // namespace bodyrec
