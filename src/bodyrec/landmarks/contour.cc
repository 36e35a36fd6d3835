#include "bodyrec/landmarks/contour.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {

std::string to_string(ContourStatus status) {
  switch (status) {
    case ContourStatus::kOk: return "ok";
    case ContourStatus::kEmpty: return "empty mask";
    case ContourStatus::kTooSmall: return "too small";
    case ContourStatus::kTouchesBorder: return "touches border";
  }
  return "?";
}

void ContourOptions::check() const {
  if (landmarks < 3 || landmarks > 10000) throw OptionError("ContourOptions", "landmarks", "must be in [3, 10000]");
  if (min_height < 1) throw OptionError("ContourOptions", "min_height", "must be >= 1 px");
  if (!(max_border_fraction >= 0 && max_border_fraction <= 1))
    throw OptionError("ContourOptions", "max_border_fraction", "must be in [0, 1]");
}

double signed_area2(const std::vector<cv::Point2d>& polygon) {
  double sum = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const cv::Point2d& a = polygon[i];
    const cv::Point2d& b = polygon[(i + 1) % polygon.size()];
    sum += a.x * b.y - b.x * a.y;
  }
  return sum;
}

namespace {

// Arc length at the start of each segment of the closed polyline, and the total at the end.
std::vector<double> cumulative_arc(const std::vector<cv::Point2d>& closed) {
  const size_t m = closed.size();
  std::vector<double> c(m + 1, 0.0);
  for (size_t i = 0; i < m; ++i) c[i + 1] = c[i] + cv::norm(closed[(i + 1) % m] - closed[i]);
  return c;
}

}  // namespace

double closed_length(const std::vector<cv::Point2d>& closed) { return cumulative_arc(closed).back(); }

std::vector<cv::Point2d> points_at_arc(const std::vector<cv::Point2d>& closed, const std::vector<double>& at) {
  std::vector<cv::Point2d> out;
  if (closed.empty()) return out;
  const size_t m = closed.size();
  const std::vector<double> cumulative = cumulative_arc(closed);
  const double total = cumulative[m];
  out.reserve(at.size());
  // `after`: the first cumulative length above s. Fractions come mostly in ascending order (resampling,
  // the arc offsets), so it is found by stepping on from the last one's, and searched for otherwise.
  size_t after = 1;
  double last = -1;
  for (double f : at) {
    const double s = total * (f - std::floor(f));
    if (s < last) after = static_cast<size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin());
    while (after <= m && cumulative[after] <= s) ++after;
    last = s;
    const size_t segment = std::min(m - 1, after - 1);
    const double length = cumulative[segment + 1] - cumulative[segment];
    const double t = length > 0 ? (s - cumulative[segment]) / length : 0.0;
    const cv::Point2d& a = closed[segment];
    const cv::Point2d& b = closed[(segment + 1) % m];
    out.push_back(a + t * (b - a));
  }
  return out;
}

std::vector<cv::Point2d> resample_closed(const std::vector<cv::Point2d>& closed, int n) {
  std::vector<double> at(static_cast<size_t>(std::max(n, 0)));
  for (int k = 0; k < n; ++k) at[static_cast<size_t>(k)] = static_cast<double>(k) / n;
  return points_at_arc(closed, at);
}

namespace {

// The outer border of the largest 8-connected component of `mask` (non-zero = in, as findContours and
// connectedComponents read it); empty when it has none. One component (nearly every body mask): its border
// traced on the mask itself, the very outline the labelled component gives; several: labelled first.
// Labelling costs twice the tracing on fitting's small masks, and fitting traces five outlines per person.
std::vector<cv::Point> largest_component_outline(const cv::Mat& mask) {
  std::vector<std::vector<cv::Point>> borders;
  std::vector<cv::Vec4i> hierarchy;
  // RETR_CCOMP puts each component's outer border at the top level, also those inside another's hole.
  cv::findContours(mask, borders, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_NONE);
  size_t outer = 0, components = 0;
  for (size_t i = 0; i < borders.size(); ++i)
    if (hierarchy[i][3] < 0) {
      outer = i;
      ++components;
    }
  if (components == 0) return {};
  if (components == 1) return std::move(borders[outer]);

  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int largest = 1;
  for (int i = 2; i < count; ++i)
    if (stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(largest, cv::CC_STAT_AREA)) largest = i;
  // One 8-connected component has one outer border.
  cv::findContours(labels == largest, borders, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  return std::move(borders.front());
}

}  // namespace

BodyContour contour_from_mask(const cv::Mat& mask, const ContourOptions& options) {
  CV_Assert(mask.type() == CV_8UC1);
  BodyContour result;
  const std::vector<cv::Point> outline = largest_component_outline(mask);
  if (outline.empty()) return result;
  result.bounds = cv::boundingRect(outline);

  int on_border = 0;
  for (const cv::Point& p : outline)
    if (p.x == 0 || p.y == 0 || p.x == mask.cols - 1 || p.y == mask.rows - 1) ++on_border;
  result.border_fraction = static_cast<double>(on_border) / static_cast<double>(outline.size());
  if (result.bounds.height < options.min_height) {
    result.status = ContourStatus::kTooSmall;
    return result;
  }
  if (result.border_fraction > options.max_border_fraction) {
    result.status = ContourStatus::kTouchesBorder;
    return result;
  }

  std::vector<cv::Point2d> closed(outline.begin(), outline.end());
  if (signed_area2(closed) < 0) std::reverse(closed.begin(), closed.end());
  const auto top_left = std::min_element(closed.begin(), closed.end(), [](const cv::Point2d& a, const cv::Point2d& b) {
    return a.y != b.y ? a.y < b.y : a.x < b.x;
  });
  std::rotate(closed.begin(), top_left, closed.end());
  result.points = resample_closed(closed, options.landmarks);
  result.status = ContourStatus::kOk;
  return result;
}

std::vector<cv::Point2d> mirror_contour(const std::vector<cv::Point2d>& points, int image_width) {
  const size_t n = points.size();
  std::vector<cv::Point2d> out(n);
  for (size_t i = 0; i < n; ++i) {
    const cv::Point2d& p = points[(n - i) % n];
    out[i] = cv::Point2d(image_width - 1 - p.x, p.y);
  }
  return out;
}

PolylineProjection project_to_closed_polyline(const cv::Point2d& p, const std::vector<cv::Point2d>& polygon) {
  PolylineProjection best{std::numeric_limits<double>::infinity(), 0.0};
  const std::vector<double> cumulative = cumulative_arc(polygon);
  for (size_t i = 0; i < polygon.size(); ++i) {
    const cv::Point2d& a = polygon[i];
    const cv::Point2d& b = polygon[(i + 1) % polygon.size()];
    const cv::Point2d ab = b - a;
    const double len2 = ab.dot(ab);
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double d = cv::norm(p - (a + t * ab));
    if (d < best.distance) best = {d, cumulative[i] + t * std::sqrt(len2)};
  }
  const double total = polygon.empty() ? 0.0 : cumulative.back();
  best.arc = total > 0 ? best.arc / total : 0.0;
  return best;
}

double distance_to_closed_polyline(const cv::Point2d& p, const std::vector<cv::Point2d>& polygon) {
  return project_to_closed_polyline(p, polygon).distance;
}

}  // namespace bodyrec
