// Body contours as landmark lists: the outline of a person's mask resampled to N points, and its mirror
// image. The numbering convention follows the thesis author's 180-landmark files (thesis_ch3): point 0 at
// the top of the head, then clockwise as seen in the image (rightwards across the top of the head first).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace bodyrec {

// Why a mask did not give a usable contour (make-contour-set reports the counts per reason).
enum class ContourStatus { kOk, kEmpty, kTooSmall, kTouchesBorder };
std::string to_string(ContourStatus status);

struct ContourOptions {
  int landmarks = 180;                // N points per contour
  int min_height = 80;                // contours shorter than this (pixels) are kTooSmall
  double max_border_fraction = 0.10;  // contours with more of their pixels on the image border are kTouchesBorder
  void check() const;                 // throws UsageError
};

struct BodyContour {
  ContourStatus status = ContourStatus::kEmpty;
  std::vector<cv::Point2d> points;  // N landmarks (empty unless kOk)
  cv::Rect bounds;                  // bounding box of the outline pixels
  double border_fraction = 0;       // share of outline pixels on the image border
};

// Outline of the largest 8-connected component of `mask` (CV_8U, non-zero = person), resampled to
// `options.landmarks` points equally spaced by arc length along the pixel outline, starting at the topmost
// outline pixel (ties: the leftmost) and running clockwise in the image. Points are pixel centres.
// REQUIRES: mask is CV_8UC1. ENSURES: status kOk <=> points.size() == options.landmarks.
BodyContour contour_from_mask(const cv::Mat& mask, const ContourOptions& options);

// `closed` resampled to `n` points equally spaced by arc length (the polygon closes back to its first
// point), starting at closed[0]. REQUIRES: closed has >= 1 point, n >= 1.
std::vector<cv::Point2d> resample_closed(const std::vector<cv::Point2d>& closed, int n);

// The points of `closed` (closing back to closed[0]) at the given fractions of its length from
// closed[0], each taken modulo 1 (-0.1 is 0.9). Empty when closed is.
std::vector<cv::Point2d> points_at_arc(const std::vector<cv::Point2d>& closed, const std::vector<double>& at);

// The length of the closed polyline `closed` (back to its first point); 0 when it has fewer than 2 points.
double closed_length(const std::vector<cv::Point2d>& closed);

// Twice the signed area (shoelace) in image coordinates (y down): > 0 when clockwise on screen.
double signed_area2(const std::vector<cv::Point2d>& polygon);

// The landmarks of the left-right mirrored image of width `image_width` (column c -> image_width-1-c):
// point 0 stays the mirror of point 0 (the head top) and the order is reversed so that it stays clockwise.
// mirror_contour(mirror_contour(p, w), w) == p.
std::vector<cv::Point2d> mirror_contour(const std::vector<cv::Point2d>& points, int image_width);

// The nearest point to `p` on the closed polyline `polygon` (any of its segments): its distance, and
// where it lies as a fraction of the length from polygon[0] (0..1).
struct PolylineProjection {
  double distance = 0;
  double arc = 0;
};
PolylineProjection project_to_closed_polyline(const cv::Point2d& p, const std::vector<cv::Point2d>& polygon);

// Distance from `p` to the closed polyline `polygon` (nearest point on any of its segments).
double distance_to_closed_polyline(const cv::Point2d& p, const std::vector<cv::Point2d>& polygon);

}  // namespace bodyrec
