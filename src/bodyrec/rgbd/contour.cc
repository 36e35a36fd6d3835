#include "bodyrec/rgbd/contour.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"
#include "bodyrec/rgbd/recording.h"

namespace bodyrec {
namespace {

// The largest 8-connected part of label == `label` as a 0/255 mask, or empty when there is none.
cv::Mat largest_part(const cv::Mat& labels, int label) {
  cv::Mat mask = labels == label;
  cv::Mat comp, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, comp, stats, centroids, 8, CV_32S);
  if (n < 2) return {};
  int best = 1;
  for (int i = 2; i < n; ++i)
    if (stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = i;
  return comp == best;
}

double signed_area(const std::vector<cv::Point>& c) {
  double a = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    const cv::Point& p = c[i];
    const cv::Point& q = c[(i + 1) % c.size()];
    a += static_cast<double>(p.x) * q.y - static_cast<double>(q.x) * p.y;
  }
  return a;  // > 0: clockwise on the image (y down)
}

}  // namespace

ContourMethod parse_contour_method(const std::string& name) {
  if (name == "ccd") return ContourMethod::kCcd;
  if (name == "opencv") return ContourMethod::kOpenCv;
  throw UsageError("unknown contour method '" + name + "' (ccd or opencv)");
}

void ccd_contour(const cv::Mat& labels, cv::Mat& contour) {
  CV_Assert(labels.type() == CV_8U);
  contour.create(labels.size(), CV_8U);
  contour.setTo(cv::Scalar(kNoBody));
  const int w = labels.cols, h = labels.rows;
  for (int y = 1; y < h - 1; ++y) {
    const uint8_t* up = labels.ptr<uint8_t>(y - 1);
    const uint8_t* row = labels.ptr<uint8_t>(y);
    const uint8_t* down = labels.ptr<uint8_t>(y + 1);
    uint8_t* out = contour.ptr<uint8_t>(y);
    for (int x = 1; x < w - 1; ++x) {
      const uint8_t b = row[x];
      if (b == kNoBody) continue;
      if (row[x - 1] != b || row[x + 1] != b || up[x] != b || down[x] != b) out[x] = b;
    }
  }
}

std::vector<cv::Point> trace_outline(const cv::Mat& labels, int label) {
  CV_Assert(labels.type() == CV_8U);
  const cv::Mat part = largest_part(labels, label);
  if (part.empty()) return {};
  const int w = part.cols, h = part.rows;
  const auto inside = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && part.at<uint8_t>(y, x); };
  cv::Point start(-1, -1);
  for (int y = 0; y < h && start.x < 0; ++y)
    for (int x = 0; x < w; ++x)
      if (part.at<uint8_t>(y, x)) {
        start = {x, y};
        break;
      }
  // Neighbours clockwise on the image (y down), starting west.
  static const cv::Point kDir[8] = {{-1, 0}, {-1, -1}, {0, -1}, {1, -1}, {1, 0}, {1, 1}, {0, 1}, {-1, 1}};
  std::vector<cv::Point> out{start};
  cv::Point c = start;
  int back = 0;  // direction from c to the last background pixel checked (west of the start is outside)
  const size_t limit = 4 * static_cast<size_t>(w) * static_cast<size_t>(h);
  for (size_t step = 0; step < limit; ++step) {
    int found = -1;
    for (int k = 1; k <= 8; ++k) {
      const int d = (back + k) % 8;
      if (inside(c.x + kDir[d].x, c.y + kDir[d].y)) {
        found = d;
        break;
      }
    }
    if (found < 0) break;  // a single pixel
    const cv::Point next = c + kDir[found];
    // Done when the start is left the way it was left first (it may be passed more than once).
    if (c == start && out.size() > 1 && next == out[1]) break;
    const cv::Point rel = c + kDir[(found + 7) % 8] - next;  // last background checked, seen from next
    for (int d = 0; d < 8; ++d)
      if (kDir[d] == rel) back = d;
    c = next;
    out.push_back(c);
  }
  // The trace may revisit the start; drop a closing duplicate.
  while (out.size() > 1 && out.back() == start) out.pop_back();
  return out;
}

std::vector<cv::Point> opencv_outline(const cv::Mat& labels, int label) {
  CV_Assert(labels.type() == CV_8U);
  const cv::Mat part = largest_part(labels, label);
  if (part.empty()) return {};
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(part, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  if (contours.empty()) return {};
  auto best = std::max_element(contours.begin(), contours.end(),
                               [](const auto& a, const auto& b) { return a.size() < b.size(); });
  std::vector<cv::Point> c = *best;
  if (signed_area(c) < 0) std::reverse(c.begin(), c.end());
  return c;
}

std::vector<cv::Point2d> contour_landmarks(const std::vector<cv::Point>& outline, int n) {
  if (outline.empty() || n < 1) return {};
  std::vector<cv::Point> c = outline;
  if (signed_area(c) < 0) std::reverse(c.begin(), c.end());
  // Point 0: the middle of the first run of topmost pixels along the outline.
  int top = c[0].y;
  for (const auto& p : c) top = std::min(top, p.y);
  size_t run_start = 0;
  while (!(c[run_start].y == top && c[(run_start + c.size() - 1) % c.size()].y != top) && run_start + 1 < c.size())
    ++run_start;
  if (c[run_start].y != top)  // the whole outline is one row
    run_start = 0;
  size_t run_len = 0;
  while (run_len < c.size() && c[(run_start + run_len) % c.size()].y == top) ++run_len;
  std::rotate(c.begin(), c.begin() + static_cast<long>((run_start + run_len / 2) % c.size()), c.end());
  std::vector<double> cum(c.size() + 1, 0.0);
  for (size_t i = 0; i < c.size(); ++i) cum[i + 1] = cum[i] + cv::norm(c[(i + 1) % c.size()] - c[i]);
  const double total = cum.back();
  std::vector<cv::Point2d> out;
  out.reserve(static_cast<size_t>(n));
  size_t seg = 0;
  for (int k = 0; k < n; ++k) {
    const double s = total * k / n;
    while (seg + 1 < c.size() && cum[seg + 1] <= s) ++seg;
    const cv::Point2d a = c[seg], b = c[(seg + 1) % c.size()];
    const double len = cum[seg + 1] - cum[seg];
    const double t = len > 0 ? (s - cum[seg]) / len : 0.0;
    out.push_back(a + (b - a) * t);
  }
  return out;
}

std::vector<BodyContour> body_contours(const cv::Mat& labels, const cv::Mat& depth, const Intrinsics& k,
                                       double unit, int n, ContourMethod method) {
  if (labels.type() != CV_8U || labels.cols != k.width || labels.rows != k.height)
    throw InputError("contour: labels must be 8-bit " + std::to_string(k.width) + "x" + std::to_string(k.height));
  if (depth.type() != CV_16U || depth.size() != labels.size())
    throw InputError("contour: depth must be 16-bit of the labels' size");
  if (n < 1) throw UsageError("contour: --landmarks must be at least 1");
  bool present[kMaxBodies] = {};
  for (int y = 0; y < labels.rows; ++y) {
    const uint8_t* r = labels.ptr<uint8_t>(y);
    for (int x = 0; x < labels.cols; ++x)
      if (r[x] < kMaxBodies) present[r[x]] = true;
  }
  std::vector<BodyContour> out;
  for (int b = 0; b < kMaxBodies; ++b) {
    if (!present[b]) continue;
    BodyContour bc;
    bc.label = b;
    bc.outline = method == ContourMethod::kCcd ? trace_outline(labels, b) : opencv_outline(labels, b);
    bc.landmarks = contour_landmarks(bc.outline, n);
    for (const auto& p : bc.landmarks) {
      const int px = static_cast<int>(std::lround(p.x)), py = static_cast<int>(std::lround(p.y));
      std::optional<cv::Vec3d> best;
      int best_d = 1 << 30;
      for (int dy = -3; dy <= 3; ++dy)
        for (int dx = -3; dx <= 3; ++dx) {
          const int x = px + dx, y = py + dy;
          if (x < 0 || y < 0 || x >= labels.cols || y >= labels.rows) continue;
          if (labels.at<uint8_t>(y, x) != b) continue;
          const uint16_t d = depth.at<uint16_t>(y, x);
          if (!d || dx * dx + dy * dy >= best_d) continue;
          best_d = dx * dx + dy * dy;
          best = unproject(k, x, y, d * unit);
        }
      bc.points.push_back(best);
    }
    out.push_back(std::move(bc));
  }
  return out;
}

}  // namespace bodyrec
