// Groups run sections: who led, who walked together, where the leaders went, what it looked like.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "bodyrec/report/html.h"
#include "bodyrec/report/sections.h"
#include "bodyrec/report/svg.h"

namespace bodyrec::report {
namespace {

std::string role_name(const std::string& role) { return role == "potential-member" ? "potential member" : role; }

Section role_timeline(const RunData& run) {
  struct Open {
    std::string role;
    int begin = 0, last = 0;
  };
  std::map<int, StripRow> rows;
  std::map<int, Open> open;
  auto close = [&](int id) {
    const Open& o = open[id];
    rows[id].segments.push_back({static_cast<double>(o.begin), static_cast<double>(o.last + 1), role_colour(o.role),
                                 "track " + std::to_string(id) + ": " + role_name(o.role) + ", frames " +
                                     std::to_string(o.begin) + "–" + std::to_string(o.last)});
    open.erase(id);
  };
  int previous_frame = -1;
  for (const auto& row : run.groups) {
    for (const auto& p : row.people) {
      rows[p.id].label = "#" + std::to_string(p.id);
      const auto it = open.find(p.id);
      if (it != open.end() && it->second.role == p.role && it->second.last == previous_frame) {
        it->second.last = row.frame;
        continue;
      }
      if (it != open.end()) close(p.id);
      open[p.id] = {p.role, row.frame, row.frame};
    }
    for (auto it = open.begin(); it != open.end();) {  // tracks absent from this row end here
      const int id = it->first;
      ++it;
      if (open[id].last != row.frame) close(id);
    }
    previous_frame = row.frame;
  }
  while (!open.empty()) close(open.begin()->first);
  std::vector<StripRow> strips;
  for (auto& [id, r] : rows) strips.push_back(std::move(r));
  const double x0 = run.groups.front().frame, x1 = run.groups.back().frame + 1;
  Section s{"roles", "Roles over time", ""};
  s.html = "<p>One row per track (" + std::to_string(strips.size()) +
           " tracks), coloured by the role the pipeline gave it in each frame; gaps are frames without the track. "
           "Hover a bar for its frames.</p>" +
           html_legend({{role_colour("leader"), "leader"},
                        {role_colour("member"), "member"},
                        {role_colour("non-member"), "non-member"},
                        {role_colour("potential-member"), "potential member"}}) +
           strip_timeline(strips, x0, x1, "frame", strips.size() > 60 ? 8 : 12);
  return s;
}

Section group_counts(const RunData& run) {
  Series people{"people", "#64748b", {}, {}, true, false}, groups{"groups", "#2563eb", {}, {}, true, false},
      largest{"largest group", "#16a34a", {}, {}, true, false};
  int most_groups = 0, biggest = 0;
  for (const auto& row : run.groups) {
    std::map<int, int> sizes;
    for (const auto& p : row.people)
      if (p.group >= 0) ++sizes[p.group];
    int big = 0;
    for (const auto& [g, n] : sizes) big = std::max(big, n);
    people.x.push_back(row.frame);
    people.y.push_back(static_cast<double>(row.people.size()));
    groups.x.push_back(row.frame);
    groups.y.push_back(static_cast<double>(sizes.size()));
    largest.x.push_back(row.frame);
    largest.y.push_back(big);
    most_groups = std::max<int>(most_groups, static_cast<int>(sizes.size()));
    biggest = std::max(biggest, big);
  }
  PlotFrame frame;
  frame.x_label = "frame";
  frame.y_label = "count";
  Section s{"groups", "Groups over time", ""};
  s.html = "<p>People tracked, groups formed and the size of the largest group in every frame (at most " +
           std::to_string(most_groups) + (most_groups == 1 ? " group" : " groups") + " at once; largest group " +
           std::to_string(biggest) + " people).</p>" +
           html_legend({{people.colour, people.name}, {groups.colour, groups.name}, {largest.colour, largest.name}}) +
           line_plot({people, groups, largest}, frame);
  return s;
}

Section direction_rose(const RunData& run) {
  constexpr int kSectors = 16;
  std::vector<double> weights(kSectors, 0.0);
  int samples = 0;
  for (const auto& row : run.groups)
    for (const auto& l : row.leaders) {
      if (!l.degrees || l.magnitude <= 0) continue;
      double d = std::fmod(*l.degrees, 360.0);
      if (d < 0) d += 360;
      weights[static_cast<int>(std::lround(d / (360.0 / kSectors))) % kSectors] += l.magnitude;
      ++samples;
    }
  Section s{"directions", "Leader walking directions", ""};
  if (samples == 0) {
    s.html = "<p class=\"note\">No leader direction in this run (no leader was tracked long enough).</p>";
    return s;
  }
  const int best = static_cast<int>(std::max_element(weights.begin(), weights.end()) - weights.begin());
  s.html = "<div class=\"side\"><div class=\"rose\">" + polar_rose(weights, role_colour("leader")) +
           "</div><p>Where the leaders walked, in image directions: each petal sums the flow magnitude "
           "(pixels per frame) of the leader frames heading that way (" +
           std::to_string(samples) + " leader frames, " + std::to_string(kSectors) +
           " sectors; petal area is proportional to the sum). Most movement heads " +
           fmt(best * 360.0 / kSectors, 0) + "° (0° = right, 90° = up).</p></div>";
  return s;
}

}  // namespace

void add_groups_sections(const ReportInput& input, std::vector<Section>& out) {
  out.push_back(role_timeline(input.run));
  out.push_back(group_counts(input.run));
  out.push_back(direction_rose(input.run));
  out.push_back(key_frames_section(input));
}

}  // namespace bodyrec::report
