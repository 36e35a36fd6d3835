// Body outlines from a label image (a body index, or a depth-only Segmentation's labels) and contour
// landmarks with camera-space positions.
//
// CCD kernel (thesis digest Ch5, "Conditional Contour Detector"): pixel p at x in 1..w-2, y in 1..h-2
// is a contour pixel iff it belongs to a body and one of its 4 neighbours (left, right, up, down) does
// not belong to that body. The thesis tests "neighbour == 0xFF" with one body in view; testing "not this
// body" gives each of several touching bodies its own closed outline and is identical otherwise.
// Outlines for landmarks: "ccd" traces the CCD pixels of a body's largest 8-connected part in order
// (Moore-neighbour tracing, our own code); "opencv" takes cv::findContours' external contour of it.
// Landmarks follow the Ch3 convention: N points at equal arc length, point 0 at the top of the outline,
// clockwise as seen on the image.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "bodyrec/rgbd/camera.h"

namespace bodyrec {

enum class ContourMethod { kCcd, kOpenCv };
// "ccd" or "opencv"; UsageError otherwise.
ContourMethod parse_contour_method(const std::string& name);

// The CCD kernel over a label image (CV_8U, 0..5 body, 255 none): `contour` (CV_8U, same size) holds
// the body's label at contour pixels and 255 elsewhere (the image border is never a contour pixel).
void ccd_contour(const cv::Mat& labels, cv::Mat& contour);

// Ordered outline (clockwise on the image, starting at the top-left-most pixel) of the largest
// 8-connected part of the pixels == label, by Moore-neighbour tracing. Empty when the label is absent.
std::vector<cv::Point> trace_outline(const cv::Mat& labels, int label);

// The same outline from cv::findContours (external contour of the largest part), clockwise.
std::vector<cv::Point> opencv_outline(const cv::Mat& labels, int label);

// N points at equal arc length along the closed outline, point 0 at the top (smallest y; the middle of
// the topmost run of pixels), clockwise on the image. Empty when the outline is empty or n < 1.
std::vector<cv::Point2d> contour_landmarks(const std::vector<cv::Point>& outline, int n);

struct BodyContour {
  int label = 0;
  std::vector<cv::Point> outline;
  std::vector<cv::Point2d> landmarks;             // depth pixels
  std::vector<std::optional<cv::Vec3d>> points;   // camera space (metres); nullopt: no depth nearby
};

// Outlines and N landmarks of every body in `labels`; a landmark's 3D point is the unprojection of the
// nearest pixel of the same body with valid depth within 3 pixels.
// REQUIRES labels CV_8U and depth CV_16U of the depth intrinsics' size (InputError otherwise), n >= 1.
std::vector<BodyContour> body_contours(const cv::Mat& labels, const cv::Mat& depth, const Intrinsics& depth_k,
                                       double depth_unit_m, int n, ContourMethod method);

}  // namespace bodyrec
