#include "bodyrec/reid/partial_scan.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {

double mask_sharpness(const cv::Mat& bgr, const cv::Mat& mask, int erode_px, double ref) {
  cv::Mat grey, lap, inner;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  cv::Laplacian(grey, lap, CV_32F, 3);
  cv::erode(mask, inner, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(erode_px, erode_px)));
  if (cv::countNonZero(inner) < 50) inner = mask;
  cv::Scalar mean, stddev;
  cv::meanStdDev(lap, mean, stddev, inner);
  const double var = stddev[0] * stddev[0];
  return var / (var + ref);
}
namespace {

// Largest 8-connected part of a binary mask, in place.
void keep_largest(cv::Mat& mask) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  if (n <= 2) return;
  int best = 1;
  for (int i = 2; i < n; ++i)
    if (stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(best, cv::CC_STAT_AREA)) best = i;
  mask = labels == best;
}

}  // namespace

PartialScanExtractor::PartialScanExtractor(const RecordingMeta& meta, PartialScanOptions options)
    : meta_(meta), options_(options) {
  meta_.depth.check("depth intrinsics");
  meta_.color.check("colour intrinsics");
  ray_x_.resize(static_cast<size_t>(meta_.depth.width));
  ray_y_.resize(static_cast<size_t>(meta_.depth.height));
  for (int u = 0; u < meta_.depth.width; ++u)
    ray_x_[static_cast<size_t>(u)] = static_cast<float>((u - meta_.depth.cx) / meta_.depth.fx);
  for (int v = 0; v < meta_.depth.height; ++v)
    ray_y_[static_cast<size_t>(v)] = static_cast<float>((meta_.depth.cy - v) / meta_.depth.fy);
}

cv::Mat PartialScanExtractor::color_mask(const RgbdFrame& frame, const BodyRef& ref, double* in_colour,
                                         const GroundPlane* ground, cv::Mat* heights) const {
  const cv::Mat& d = frame.depth;
  const cv::Mat& l = ref.labels;
  if (d.type() != CV_16U || d.cols != meta_.depth.width || d.rows != meta_.depth.height)
    throw InputError("partial scan: frame " + std::to_string(frame.index) + ": depth must be CV_16U of the depth size");
  if (l.type() != CV_8U || l.size() != d.size())
    throw InputError("partial scan: frame " + std::to_string(frame.index) + ": labels must be CV_8U of the depth size");
  const Intrinsics& kc = meta_.color;
  const cv::Matx33f r = meta_.depth_to_color.rotation;
  const cv::Vec3f t = meta_.depth_to_color.translation;
  const float unit = static_cast<float>(meta_.depth_unit_m);
  // A depth pixel covers about fx_c / fx_d colour pixels (same distance); splat squares of that size.
  const int half = std::max(1, static_cast<int>(std::ceil(0.5 * kc.fx / meta_.depth.fx)));
  cv::Mat mask(kc.height, kc.width, CV_8U, cv::Scalar(0));
  const bool with_heights = ground && heights;
  if (with_heights) heights->create(kc.height, kc.width, CV_32F), heights->setTo(cv::Scalar(std::nanf("")));
  int bu0 = kc.width, bu1 = -1, bv0 = kc.height, bv1 = -1;  // bounding box of the splats
  int body = 0, inside = 0;  // the body's depth pixels, and those landing in the colour image
  bool at_edge = false;      // the body touches the depth image's left or right border (cut off)
  for (int v = 0; v < d.rows; ++v) {
    const uint8_t* lab = l.ptr<uint8_t>(v);
    const uint16_t* dep = d.ptr<uint16_t>(v);
    for (int u = 0; u < d.cols; ++u) {
      if (lab[u] != ref.label || dep[u] == 0) continue;
      ++body;
      at_edge |= u == 0 || u == d.cols - 1;
      const float z = dep[u] * unit;
      const cv::Vec3f pd(ray_x_[static_cast<size_t>(u)] * z, ray_y_[static_cast<size_t>(v)] * z, z);
      const cv::Vec3f p = r * pd + t;
      const float height = with_heights ? static_cast<float>(height_above(*ground, cv::Vec3d(pd))) : 0.f;
      if (p[2] <= 0.05f) continue;
      const int cu = static_cast<int>(std::lround(kc.cx + kc.fx * p[0] / p[2]));
      const int cv_ = static_cast<int>(std::lround(kc.cy - kc.fy * p[1] / p[2]));
      inside += cu >= 0 && cu < kc.width && cv_ >= 0 && cv_ < kc.height;
      const int u0 = std::max(0, cu - half + 1), u1 = std::min(kc.width - 1, cu + half);
      const int v0 = std::max(0, cv_ - half + 1), v1 = std::min(kc.height - 1, cv_ + half);
      for (int y = v0; y <= v1; ++y) {
        uint8_t* m = mask.ptr<uint8_t>(y);
        for (int x = u0; x <= u1; ++x) m[x] = 255;
        if (with_heights) {
          float* hp = heights->ptr<float>(y);
          for (int x = u0; x <= u1; ++x) hp[x] = height;
        }
      }
      if (u0 > u1 || v0 > v1) continue;
      bu0 = std::min(bu0, u0), bu1 = std::max(bu1, u1), bv0 = std::min(bv0, v0), bv1 = std::max(bv1, v1);
    }
  }
  // A body cut off by the depth image's side shows only part of itself: count it half.
  if (in_colour) *in_colour = body ? static_cast<double>(inside) / body * (at_edge ? 0.5 : 1.0) : 0.0;
  if (bu1 < 0) return {};
  // Close the holes of depth dropouts, then keep the largest part (stray edge pixels go).
  const cv::Rect box(bu0, bv0, bu1 - bu0 + 1, bv1 - bv0 + 1);
  const int k = 2 * half + 3;
  const cv::Rect grown = cv::Rect(box.x - k, box.y - k, box.width + 2 * k, box.height + 2 * k) & cv::Rect(0, 0, kc.width, kc.height);
  cv::Mat roi = mask(grown);
  cv::morphologyEx(roi, roi, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
  cv::Mat part = roi.clone();
  keep_largest(part);
  part.copyTo(roi);
  return mask;
}

std::optional<PartialScan> PartialScanExtractor::extract(const RgbdFrame& frame, const BodyRef& ref,
                                                         const ViewEstimate& view, std::string* why,
                                                         const GroundPlane* ground) const {
  const auto fail = [&](const std::string& reason) -> std::optional<PartialScan> {
    if (why) *why = reason;
    return std::nullopt;
  };
  if (frame.color.empty()) return fail("no colour image");
  if (frame.depth.empty() || ref.labels.empty()) return fail("no depth or no body pixels");
  if (frame.color.type() != CV_8UC3 || frame.color.cols != meta_.color.width || frame.color.rows != meta_.color.height)
    throw InputError("partial scan: frame " + std::to_string(frame.index) + ": colour must be CV_8UC3 of the colour size");
  double in_colour = 0;
  cv::Mat heights;
  const cv::Mat full = color_mask(frame, ref, &in_colour, ground, &heights);
  if (full.empty()) return fail("the body has no pixels with depth");
  const cv::Rect tight = cv::boundingRect(full);
  const int pixels = cv::countNonZero(full(tight));
  if (pixels < options_.min_pixels) return fail("the body covers only " + std::to_string(pixels) + " colour pixels");

  PartialScan s;
  s.view = view;
  s.pixels = pixels;
  s.in_colour = in_colour;
  const int m = options_.margin_px;
  s.box = cv::Rect(tight.x - m, tight.y - m, tight.width + 2 * m, tight.height + 2 * m) &
          cv::Rect(0, 0, frame.color.cols, frame.color.rows);
  s.mask = full(s.box).clone();
  s.image = cv::Mat(s.box.size(), CV_8UC3, cv::Scalar(0, 0, 0));
  frame.color(s.box).copyTo(s.image, s.mask);
  if (ground) {
    // Per row, the median height of the points splatted into its mask pixels (the closing step fills
    // pixels that got none).
    s.row_height_m.assign(static_cast<size_t>(s.box.height), std::nanf(""));
    std::vector<float> row;
    for (int y = 0; y < s.box.height; ++y) {
      row.clear();
      const float* hp = heights.ptr<float>(s.box.y + y) + s.box.x;
      const uint8_t* m = s.mask.ptr<uint8_t>(y);
      for (int x = 0; x < s.box.width; ++x)
        if (m[x] && std::isfinite(hp[x])) row.push_back(hp[x]);
      if (row.empty()) continue;
      std::nth_element(row.begin(), row.begin() + static_cast<long>(row.size() / 2), row.end());
      s.row_height_m[static_cast<size_t>(y)] = row[row.size() / 2];
    }
  }

  s.sharpness = mask_sharpness(frame.color(s.box), s.mask, 7, options_.sharpness_ref);
  s.resolution = std::min(1.0, tight.height / (0.5 * meta_.color.height));

  // Completeness.
  const bool touches = tight.x <= 0 || tight.y <= 0 || tight.br().x >= frame.color.cols ||
                       tight.br().y >= frame.color.rows;
  if (ref.body) {
    const auto visible = [&](int j) {
      const BodyJoint& bj = ref.body->joints[static_cast<size_t>(j)];
      if (bj.tracking_state == 0) return false;
      const auto pd = project(meta_.depth, bj.position);
      const auto pc = project(meta_.color, meta_.depth_to_color.apply(bj.position));
      if (!pd || !pc || pc->x < 0 || pc->y < 0 || pc->x >= meta_.color.width || pc->y >= meta_.color.height) return false;
      const int u = cvRound(pd->x), v = cvRound(pd->y);
      for (int y = std::max(0, v - 2); y <= std::min(ref.labels.rows - 1, v + 2); ++y)
        for (int x = std::max(0, u - 2); x <= std::min(ref.labels.cols - 1, u + 2); ++x)
          if (ref.labels.at<uint8_t>(y, x) == ref.label) return true;
      return false;
    };
    int tracked = 0, seen = 0;
    for (int j = 0; j < kJointCount; ++j) {
      if (ref.body->joints[static_cast<size_t>(j)].tracking_state == 0) continue;
      ++tracked;
      seen += visible(j);
    }
    s.head = visible(idx(Joint::kHead));
    s.feet = visible(idx(Joint::kFootLeft)) || visible(idx(Joint::kAnkleLeft));
    s.feet = s.feet && (visible(idx(Joint::kFootRight)) || visible(idx(Joint::kAnkleRight)));
    s.completeness = tracked ? static_cast<double>(seen) / tracked : 0.0;
    // Without heights a descriptor places colours by image row: a body cut at the head or feet would
    // misplace them. With heights (row_height_m) the visible part stays where it belongs.
    if ((!s.head || !s.feet) && !ground) s.completeness *= 0.5;
  } else {
    const auto a = depth_axis(frame.depth, meta_.depth_unit_m, meta_.depth, ref.labels, ref.label);
    const double height = a ? a->height_m : 0.0;
    s.head = tight.y > 0;
    s.feet = tight.br().y < frame.color.rows;
    s.completeness = std::min(1.0, height / 1.6) * (touches ? 0.6 : 1.0) * in_colour;
  }
  s.quality = s.completeness * (0.5 + 0.5 * s.sharpness) * (0.5 + 0.5 * s.resolution);
  return s;
}

}  // namespace bodyrec
