#include "bodyrec/groups/leader_direction.h"

#include <cmath>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "bodyrec/core/error.h"

namespace bodyrec {

void LeaderDirectionOptions::check() const {
  const auto fail = [](const char* field, const char* problem) { throw OptionError("LeaderDirectionOptions", field, problem); };
  if (window < 1) fail("window", "must be >= 1 frame");
  if (!(work_height >= 16)) fail("work_height", "must be >= 16 px");
  if (!(torso_y > 0 && torso_y < 1)) fail("torso_y", "must be in (0, 1)");
  if (!(torso_size > 0 && torso_size <= 1)) fail("torso_size", "must be in (0, 1]");
}

double flow_degrees(const cv::Point2d& flow) {
  double d = std::atan2(-flow.y, flow.x) * 180.0 / CV_PI;
  if (d < 0) d += 360.0;
  return d >= 360.0 ? 0.0 : d;
}

LeaderDirection::LeaderDirection(const LeaderDirectionOptions& options) : options_(options) { options_.check(); }

std::optional<Direction> LeaderDirection::update(const cv::Mat& previous, const cv::Mat& current, const Box& box) {
  if (previous.empty() || previous.size() != current.size()) return std::nullopt;
  const cv::Rect roi = cv::Rect(clip_box(box, current.size()));
  if (roi.width < 8 || roi.height < 16) return std::nullopt;
  const double f = options_.work_height / roi.height;
  cv::Mat a, b, flow;
  cv::resize(previous(roi), a, cv::Size(), f, f, cv::INTER_AREA);
  cv::resize(current(roi), b, cv::Size(), f, f, cv::INTER_AREA);
  // Pyramid 0.5 x 3 levels, window 15: the OpenCV sample's settings, which suit walking people at this size.
  cv::calcOpticalFlowFarneback(a, b, flow, 0.5, 3, 15, 3, 5, 1.2, 0);

  const cv::Point2d torso(box.x + box.width / 2, box.y + options_.torso_y * box.height);
  const double half_w = options_.torso_size * box.width / 2, half_h = options_.torso_size * box.height / 2;
  cv::Rect patch(cv::Point(static_cast<int>((torso.x - half_w - roi.x) * f), static_cast<int>((torso.y - half_h - roi.y) * f)),
                 cv::Point(static_cast<int>(std::ceil((torso.x + half_w - roi.x) * f)),
                           static_cast<int>(std::ceil((torso.y + half_h - roi.y) * f))));
  patch &= cv::Rect(0, 0, flow.cols, flow.rows);
  if (patch.area() <= 0) return std::nullopt;
  const cv::Scalar mean = cv::mean(flow(patch));
  flows_.emplace_back(mean[0] / f, mean[1] / f);
  while (static_cast<int>(flows_.size()) > options_.window) flows_.pop_front();

  Direction d;
  for (const auto& v : flows_) d.flow += v;
  d.flow *= 1.0 / static_cast<double>(flows_.size());
  d.degrees = flow_degrees(d.flow);
  d.magnitude = std::hypot(d.flow.x, d.flow.y);
  d.torso = torso;
  d.samples = static_cast<int>(flows_.size());
  return d;
}

}  // namespace bodyrec
