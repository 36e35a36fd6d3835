// Re-identification run sections: the gallery's users, what happened when, and who each body was.
#include <algorithm>
#include <map>
#include <set>

#include "bodyrec/report/html.h"
#include "bodyrec/report/sections.h"
#include "bodyrec/report/svg.h"

namespace bodyrec::report {
namespace {

// reid/view.h kAllViews order.
const char* const kViewNames[8] = {"F", "FR", "FL", "SR", "SL", "B", "BR", "BL"};

std::string seconds(double s) { return fmt(s, 1) + " s"; }

std::string user_colour(const std::optional<int>& user) { return user ? palette(*user) : "#cbd5e1"; }

}  // namespace

Section users_section(const ReportInput& input) {
  Section s{"users", "Gallery users", ""};
  if (input.users.empty()) {
    s.html = "<p class=\"note\">The gallery holds no users.</p>";
    return s;
  }
  int scans = 0;
  for (const auto& u : input.users)
    for (const auto& v : u.views) scans += !v.empty();
  s.html = "<p>" + std::to_string(input.users.size()) + " users, " + std::to_string(scans) +
           " partial scans of 8 possible views each (F front, FR/FL front-right/left, SR/SL side, B back, "
           "BR/BL back-right/left); dashed slots have no scan yet.</p><div class=\"users\">";
  for (const auto& u : input.users) {
    s.html += "<div class=\"user\"><div class=\"who\"><b style=\"color:" + std::string(palette(u.id)) + "\">" +
              html_escape(u.label.empty() ? "user " + std::to_string(u.id) : u.label) + "</b><span>id " +
              std::to_string(u.id) + "</span><span>first seen " + seconds(u.first_seen) + "</span><span>last seen " +
              seconds(u.last_seen) + "</span></div>";
    for (int v = 0; v < 8; ++v) {
      const cv::Mat& image = u.views[v];
      std::string cell;
      if (image.empty()) cell = "<div class=\"empty\">no scan</div>";
      else if (!input.images) cell = "<div class=\"empty withheld\">scan (image left out)</div>";
      else cell = "<img alt=\"" + std::string(kViewNames[v]) + "\" src=\"" + jpeg_data_uri(image, 160) + "\">";
      s.html += "<figure class=\"view\">" + cell + "<figcaption>" + kViewNames[v] + "</figcaption></figure>";
    }
    s.html += "</div>";
  }
  s.html += "</div>";
  return s;
}

namespace {

const std::map<std::string, std::string>& event_colours() {
  static const std::map<std::string, std::string> colours = {
      {"enrolled", "#2563eb"}, {"recognised", "#16a34a"}, {"view_added", "#f59e0b"}, {"left", "#64748b"}};
  return colours;
}

Section events_section(const RunData& run) {
  Section s{"events", "Identification events", ""};
  std::set<int> users;
  int count = 0;
  for (const auto& row : run.reid)
    for (const auto& e : row.events) {
      if (e.user) users.insert(*e.user);
      ++count;
    }
  if (count == 0) {
    s.html = "<p class=\"note\">No events in this run.</p>";
    return s;
  }
  std::vector<std::string> labels;
  std::map<int, int> row_of;
  for (int u : users) {
    row_of[u] = static_cast<int>(labels.size());
    labels.push_back("user " + std::to_string(u));
  }
  const bool unknown_row = std::any_of(run.reid.begin(), run.reid.end(), [](const ReidFrameRow& r) {
    return std::any_of(r.events.begin(), r.events.end(), [](const ReidEvent& e) { return !e.user; });
  });
  if (unknown_row) labels.push_back("no user");
  std::vector<EventPoint> points;
  std::vector<std::vector<std::string>> table;
  for (const auto& row : run.reid)
    for (const auto& e : row.events) {
      const auto colour = event_colours().count(e.kind) ? event_colours().at(e.kind) : "#a855f7";
      std::string title = e.kind + " frame " + std::to_string(row.frame) + " track " + std::to_string(e.track);
      if (!e.view.empty()) title += " view " + e.view;
      if (e.score) title += " score " + fmt(*e.score, 2);
      points.push_back({static_cast<double>(row.frame), e.user ? row_of[*e.user] : static_cast<int>(labels.size()) - 1,
                        colour, title});
      if (table.size() < 200)
        table.push_back({std::to_string(row.frame), fmt(row.time, 2), e.kind,
                         e.user ? std::to_string(*e.user) : "–", e.track >= 0 ? std::to_string(e.track) : "–",
                         e.view.empty() ? "–" : e.view, e.score ? fmt(*e.score, 2) : "–"});
    }
  std::vector<std::pair<std::string, std::string>> legend;
  for (const auto& [kind, colour] : event_colours()) legend.emplace_back(colour, kind);
  s.html = "<p>" + std::to_string(count) + " events for " + std::to_string(users.size()) +
           " users; hover a dot for its score and view.</p>" + html_legend(legend) +
           event_timeline(points, labels, run.reid.front().frame, run.reid.back().frame + 1, "frame") +
           "<details><summary>Event list" + std::string(count > 200 ? " (first 200)" : "") + "</summary>" +
           html_table({"frame", "time (s)", "event", "user", "track", "view", "score"}, table, 3) + "</details>";
  return s;
}

Section identities_section(const RunData& run) {
  struct Open {
    std::optional<int> user;
    int begin = 0, last = 0;
  };
  std::map<int, StripRow> rows;
  std::map<int, Open> open;
  std::set<int> users;
  auto close = [&](int track) {
    const Open& o = open[track];
    rows[track].segments.push_back({static_cast<double>(o.begin), static_cast<double>(o.last + 1),
                                    user_colour(o.user),
                                    "track " + std::to_string(track) + ": " +
                                        (o.user ? "user " + std::to_string(*o.user) : std::string("not identified")) +
                                        ", frames " + std::to_string(o.begin) + "–" + std::to_string(o.last)});
    open.erase(track);
  };
  for (const auto& row : run.reid) {
    for (const auto& b : row.bodies) {
      rows[b.track].label = "track " + std::to_string(b.track);
      if (b.user) users.insert(*b.user);
      const auto it = open.find(b.track);
      if (it != open.end() && it->second.user == b.user) {
        it->second.last = row.frame;
        continue;
      }
      if (it != open.end()) close(b.track);
      open[b.track] = {b.user, row.frame, row.frame};
    }
    for (auto it = open.begin(); it != open.end();) {
      const int track = it->first;
      ++it;
      if (open[track].last != row.frame) close(track);
    }
  }
  while (!open.empty()) close(open.begin()->first);
  std::vector<StripRow> strips;
  for (auto& [track, r] : rows) strips.push_back(std::move(r));
  std::vector<std::pair<std::string, std::string>> legend;
  for (int u : users) legend.emplace_back(palette(u), "user " + std::to_string(u));
  legend.emplace_back(user_colour(std::nullopt), "not identified");
  Section s{"identities", "Identity per body", ""};
  s.html = "<p>One row per tracked body (" + std::to_string(strips.size()) +
           " tracks), coloured by the user it was identified as in each frame.</p>" + html_legend(legend) +
           strip_timeline(strips, run.reid.front().frame, run.reid.back().frame + 1, "frame");
  return s;
}

}  // namespace

void add_reid_sections(const ReportInput& input, std::vector<Section>& out) {
  out.push_back(events_section(input.run));
  out.push_back(identities_section(input.run));
}

}  // namespace bodyrec::report
