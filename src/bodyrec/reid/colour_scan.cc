#include "bodyrec/reid/colour_scan.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {

cv::Mat largest_part(const cv::Mat& mask) {
  if (mask.empty()) return {};
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  int best = 0, area = 0;
  for (int i = 1; i < n; ++i)
    if (stats.at<int>(i, cv::CC_STAT_AREA) > area) best = i, area = stats.at<int>(i, cv::CC_STAT_AREA);
  cv::Mat out = cv::Mat::zeros(mask.size(), CV_8U);
  if (best > 0) out.setTo(255, labels == best);
  return out;
}

cv::Mat ForegroundBodyMask::mask(const cv::Mat& frame, const cv::Rect& box) {
  (void)frame;
  return model_.mask_in(box);
}

void ColourScanOptions::check() const {
  if (min_pixels < 1) throw OptionError("ColourScanOptions", "min_pixels", "must be >= 1");
  if (margin_px < 0) throw OptionError("ColourScanOptions", "margin_px", "must be >= 0");
  if (!(sharpness_ref > 0)) throw OptionError("ColourScanOptions", "sharpness_ref", "must be > 0");
}

std::optional<PartialScan> colour_scan(const cv::Mat& frame, const cv::Rect& box, const cv::Mat& mask,
                                       const ViewEstimate& view, double occluded, std::optional<double> stature_m,
                                       const ColourScanOptions& options, std::string* why) {
  const auto fail = [&](const std::string& reason) -> std::optional<PartialScan> {
    if (why) *why = reason;
    return std::nullopt;
  };
  const cv::Rect image(0, 0, frame.cols, frame.rows);
  const cv::Rect b = box & image;
  if (b.empty() || mask.empty()) return fail("no body mask");
  if (mask.type() != CV_8U || mask.size() != b.size())
    throw InputError("colour scan: the mask (" + std::to_string(mask.cols) + "x" + std::to_string(mask.rows) +
                     ") does not match the box (" + std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
  const cv::Mat body = largest_part(mask);
  const int pixels = cv::countNonZero(body);
  if (pixels < options.min_pixels)
    return fail(std::to_string(pixels) + " mask pixels (fewer than " + std::to_string(options.min_pixels) + ")");
  std::vector<cv::Point> points;
  cv::findNonZero(body, points);
  const cv::Rect tight = cv::boundingRect(points) + b.tl();

  PartialScan s;
  s.view = view;
  s.pixels = pixels;
  s.in_colour = 1;
  const int m = options.margin_px;
  s.box = cv::Rect(tight.x - m, tight.y - m, tight.width + 2 * m, tight.height + 2 * m) & b;
  s.mask = body(s.box - b.tl()).clone();
  s.image = cv::Mat(s.box.size(), CV_8UC3, cv::Scalar(0, 0, 0));
  frame(s.box).copyTo(s.image, s.mask);
  if (stature_m && *stature_m > 0) {
    // Heights from the stature at the mask's top row down to 0 at its bottom row.
    s.row_height_m.assign(static_cast<size_t>(s.box.height), std::nanf(""));
    const int top = tight.y - s.box.y, rows = std::max(1, tight.height);
    for (int y = 0; y < s.box.height; ++y)
      s.row_height_m[static_cast<size_t>(y)] =
          static_cast<float>(*stature_m * std::clamp(1.0 - (y - top + 0.5) / rows, 0.0, 1.0));
  }

  s.sharpness = mask_sharpness(frame(s.box), s.mask, 5, options.sharpness_ref);
  s.resolution = std::min(1.0, tight.height / (0.5 * frame.rows));

  const bool top_or_bottom = box.y <= 0 || box.br().y >= frame.rows || tight.y <= 0 || tight.br().y >= frame.rows;
  const bool side = box.x <= 0 || box.br().x >= frame.cols;
  s.head = !(box.y <= 0 || tight.y <= 0);
  s.feet = !(box.br().y >= frame.rows || tight.br().y >= frame.rows);
  const double fill = pixels / static_cast<double>(b.area());
  s.completeness = (top_or_bottom ? 0.4 : 1.0) * (side ? 0.6 : 1.0) * std::max(0.0, 1.0 - 2.0 * occluded) *
                   std::min(1.0, fill / 0.35);
  s.quality = s.completeness * (0.5 + 0.5 * s.sharpness) * (0.5 + 0.5 * s.resolution);
  return s;
}

}  // namespace bodyrec
