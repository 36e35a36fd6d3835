// Key frames of a run: which frames to show, how each is annotated, and their section of the page.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <opencv2/imgproc.hpp>

#include "bodyrec/core/role.h"
#include "bodyrec/io/annotate.h"
#include "bodyrec/report/html.h"
#include "bodyrec/report/report.h"
#include "bodyrec/report/sections.h"

namespace bodyrec::report {
namespace {

// Leaders of a groups row being tracked (not lost).
int tracking_leaders(const GroupsFrameRow& row) {
  int n = 0;
  for (const auto& l : row.leaders) n += l.state == "tracking";
  return n;
}

// The rows that can be shown: a re-identification run's closing "end" row is not a frame.
std::vector<std::pair<double, int>> scored_frames(const RunData& run) {
  std::vector<std::pair<double, int>> scored;  // (score, frame)
  if (run.kind == RunKind::kGroups) {
    for (const auto& row : run.groups)
      scored.emplace_back(tracking_leaders(row) * 10.0 + static_cast<double>(row.people.size()), row.frame);
  } else {
    for (const auto& row : run.reid) {
      if (row.end) continue;
      int decided = 0;
      for (const auto& e : row.events) decided += e.kind == "recognised" ? 20 : e.kind == "enrolled" ? 10 : 0;
      scored.emplace_back(decided + static_cast<double>(row.bodies.size()), row.frame);
    }
  }
  return scored;
}

int reid_people(const ReidFrameRow& row) {
  int users = 0;
  for (const auto& b : row.bodies) users += b.user.has_value();
  return users;
}

}  // namespace

std::vector<int> choose_key_frames(const RunData& run, int count) {
  std::vector<std::pair<double, int>> scored = scored_frames(run);
  if (scored.empty() || count <= 0) return {};
  const auto [lo, hi] = std::minmax_element(scored.begin(), scored.end(),
                                            [](const auto& a, const auto& b) { return a.second < b.second; });
  const int span = hi->second - lo->second + 1;
  const int gap = std::max(1, span / (2 * count));
  std::stable_sort(scored.begin(), scored.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<int> chosen;
  for (const auto& [score, frame] : scored) {
    if (static_cast<int>(chosen.size()) == count) break;
    const bool far = std::all_of(chosen.begin(), chosen.end(), [&](int c) { return std::abs(c - frame) >= gap; });
    if (far) chosen.push_back(frame);
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

void annotate_groups_frame(cv::Mat& image, const GroupsFrameRow& row) {
  auto bgr = [](const std::string& role) { return role_color(parse_role(role).value_or(Role::kUnknown)); };
  for (const auto& p : row.people) {
    std::string label = std::to_string(p.id);
    if (p.group >= 0) label += " g" + std::to_string(p.group);
    draw_labelled_box(image, p.box, bgr(p.role), label, p.state == "lost" ? 1 : 2);
  }
  for (const auto& l : row.leaders) {
    if (!l.box) continue;
    cv::rectangle(image, cv::Rect(*l.box), colors::kBlue, 3, cv::LINE_AA);
    if (!l.degrees || l.magnitude <= 0.05) continue;
    // 10 frames of travel, at least 25 px, so that walking is visible (as in the annotated video).
    const double length = std::max(25.0, l.magnitude * 10.0), a = *l.degrees * CV_PI / 180.0;
    const cv::Point2d from(l.box->x + l.box->width / 2, l.box->y + l.box->height / 3);
    cv::arrowedLine(image, from, from + cv::Point2d(std::cos(a), -std::sin(a)) * length, colors::kYellow, 2,
                    cv::LINE_AA, 0, 0.25);
  }
  draw_caption(image, "frame " + std::to_string(row.frame) + "  people " + std::to_string(row.people.size()) +
                          "  leaders " + std::to_string(tracking_leaders(row)));
}

void annotate_reid_frame(cv::Mat& image, const ReidFrameRow& row) {
  const cv::Scalar undecided(160, 160, 160);
  for (const auto& b : row.bodies) {
    const std::string label = b.user ? "user " + std::to_string(*b.user) + (b.view.empty() ? "" : " " + b.view)
                                     : "track " + std::to_string(b.track);
    draw_labelled_box(image, b.box, b.user ? id_color(*b.user) : undecided, label, b.user ? 2 : 1);
  }
  draw_caption(image, "frame " + std::to_string(row.frame) + "  bodies " + std::to_string(row.bodies.size()) +
                          "  identified " + std::to_string(reid_people(row)));
}

std::string annotate_key_frame(cv::Mat& image, const RunData& run, int frame) {
  if (run.kind == RunKind::kGroups) {
    const auto row = std::find_if(run.groups.begin(), run.groups.end(), [&](const auto& r) { return r.frame == frame; });
    annotate_groups_frame(image, *row);
    const int leaders = tracking_leaders(*row);
    return "frame " + std::to_string(frame) + " · " + std::to_string(row->people.size()) + " people · " +
           std::to_string(leaders) + (leaders == 1 ? " leader" : " leaders");
  }
  const auto row =
      std::find_if(run.reid.begin(), run.reid.end(), [&](const auto& r) { return !r.end && r.frame == frame; });
  annotate_reid_frame(image, *row);
  std::string caption = "frame " + std::to_string(frame) + " · " + std::to_string(row->bodies.size()) + " bodies";
  for (const auto& e : row->events)
    if (e.user && (e.kind == "recognised" || e.kind == "enrolled"))
      caption += " · user " + std::to_string(*e.user) + " " + e.kind;
  return caption;
}

Section key_frames_section(const ReportInput& input) {
  Section s{"key-frames", "Key frames", ""};
  const auto chosen = choose_key_frames(input.run);
  std::string list;
  for (int f : chosen) list += (list.empty() ? "" : ", ") + std::to_string(f);
  const bool groups = input.run.kind == RunKind::kGroups;
  if (!input.images) {
    s.html = "<p class=\"note\">Images left out (--no-images). Frames chosen: " + list + ".</p>";
  } else if (input.key_frames.empty()) {
    s.html = std::string("<p class=\"note\">Give --source ") +
             (groups ? "VIDEO" : "with the run's input (its video, images or recording)") +
             " to see these frames annotated: " + list + ".</p>";
  } else {
    s.html = groups ? "<p>Frames with leaders and the most people, spread over the run. Boxes in role colours, the "
                      "leader's walking direction as a yellow arrow.</p>"
                    : "<p>Frames where people were recognised or enrolled, and with the most bodies, spread over "
                      "the run. Each body's box in its user's colour with the user and view; grey while its "
                      "identity is being decided.</p>";
    s.html += "<div class=\"frames\">";
    for (const auto& k : input.key_frames)
      s.html += "<figure><img alt=\"frame " + std::to_string(k.frame) + "\" src=\"" + jpeg_data_uri(k.image) +
                "\"><figcaption>" + html_escape(k.caption) + "</figcaption></figure>";
    s.html += "</div>";
  }
  return s;
}

}  // namespace bodyrec::report
