// Re-identification run sections: the gallery's users, what happened when, and who each body was.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "bodyrec/core/percentile.h"
#include "bodyrec/core/view.h"
#include "bodyrec/report/html.h"
#include "bodyrec/report/sections.h"
#include "bodyrec/report/svg.h"
#include "bodyrec/store/gallery.h"

namespace bodyrec::report {
namespace {

std::string user_colour(const std::optional<int>& user) { return user ? palette(*user) : "#cbd5e1"; }

const std::map<std::string, std::string>& event_colours() {
  static const std::map<std::string, std::string> colours = {{"enrolled", "#2563eb"},
                                                             {"recognised", "#16a34a"},
                                                             {"view_added", "#f59e0b"},
                                                             {"scan_replaced", "#a855f7"},
                                                             {"left", "#64748b"}};
  return colours;
}

std::string event_colour(const std::string& kind) {
  const auto it = event_colours().find(kind);
  return it == event_colours().end() ? "#a855f7" : it->second;
}

// "2026-11-20 13:05:00" (UTC) from seconds since the Unix epoch.
std::string utc_text(double unix_seconds) {
  std::string text = format_utc(from_unix_ms(std::llround(unix_seconds * 1000.0)));
  std::replace(text.begin(), text.end(), 'T', ' ');
  if (!text.empty() && text.back() == 'Z') text.pop_back();
  return text;
}

// One of the 8 slots: the scan's image, a placeholder for a scan without pixels, or an empty slot.
std::string view_slot(const cv::Mat& image, bool scanned, bool images, View view) {
  const std::string name = view_name(view);
  std::string cell;
  if (!images && (scanned || !image.empty()))
    cell = "<div class=\"slot withheld\" title=\"" + name + " scan\">image left out</div>";
  else if (!image.empty())
    cell = "<img class=\"scan\" alt=\"" + name + " scan\" src=\"" + jpeg_data_uri(image, 160) + "\">";
  else if (scanned)
    cell = "<div class=\"slot withheld\" title=\"" + name + " scan\">no image stored</div>";
  else
    cell = "<div class=\"slot empty\">no scan</div>";
  return "<figure class=\"view\">" + cell + "<figcaption>" + name + "</figcaption></figure>";
}

// The gallery's events of a user the run does not mention (the most recent ones when there are many).
std::string gallery_events(const ReportUser& u) {
  constexpr size_t kShown = 10;
  if (u.events.empty()) return "<div class=\"uevents note\">no events stored</div>";
  std::string out = "<div class=\"uevents\"><span class=\"from\">gallery events</span>";
  const size_t first = u.events.size() > kShown ? u.events.size() - kShown : 0;
  if (first > 0) out += "<span class=\"more\">" + std::to_string(first) + " earlier…</span>";
  for (size_t i = first; i < u.events.size(); ++i) {
    const ReportUserEvent& e = u.events[i];
    std::string text = e.kind;
    if (!e.view.empty()) text += " " + e.view;
    if (e.score) text += " · " + fmt(*e.score, 2);
    std::string title = utc_text(e.time) + " UTC";
    if (e.track) title += ", track " + std::to_string(*e.track);
    if (!e.source.empty()) title += ", " + e.source;
    out += "<span class=\"uevent\" style=\"border-color:" + event_colour(e.kind) + "\" title=\"" +
           html_escape(title) + "\">" + html_escape(text) + "<time>" + utc_text(e.time).substr(5) + "</time></span>";
  }
  return out + "</div>";
}

}  // namespace

Section users_section(const ReportInput& input) {
  Section s{"users", "Gallery users", ""};
  if (input.users.empty()) {
    s.html = "<p class=\"note\">The gallery holds no users.</p>";
    return s;
  }
  std::map<int, int> run_events;  // user -> events of this run
  for (const auto& row : input.run.reid)
    for (const auto& e : row.events)
      if (e.user) ++run_events[*e.user];
  int scans = 0;
  for (const auto& u : input.users)
    for (int v = 0; v < kViewCount; ++v) scans += u.scanned[v] || !u.views[v].empty();
  s.html = "<p>" + std::to_string(input.users.size()) + " users, " + std::to_string(scans) + " partial scans of " +
           std::to_string(kViewCount) + " possible each (F front, FR/FL front-right/left, SR/SL side right/left, "
           "B back, BR/BL back-right/left); dashed slots have no scan yet, hatched ones a scan whose image is "
           "not shown. Times are UTC.</p><div class=\"users\">";
  for (const auto& u : input.users) {
    s.html += "<div class=\"user\"><div class=\"who\"><b style=\"color:" + std::string(palette(u.id)) + "\">" +
              html_escape(u.label.empty() ? "user " + std::to_string(u.id) : u.label) + "</b><span>id " +
              std::to_string(u.id) + "</span><span>first seen <time>" + utc_text(u.first_seen) +
              "</time></span><span>last seen <time>" + utc_text(u.last_seen) + "</time></span></div>";
    for (int v = 0; v < kViewCount; ++v) s.html += view_slot(u.views[v], u.scanned[v], input.images, kAllViews[v]);
    const auto in_run = run_events.find(u.id);
    s.html += in_run == run_events.end()
                  ? gallery_events(u)
                  : "<div class=\"uevents note\">" + std::to_string(in_run->second) +
                        (in_run->second == 1 ? " event" : " events") + " in this run: see <a href=\"#events\">Identification events</a></div>";
    s.html += "</div>";
  }
  s.html += "</div>";
  return s;
}

namespace {

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
      const auto colour = event_colour(e.kind);
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
  std::set<std::string> kinds;  // the legend names only what the run has
  for (const auto& row : run.reid)
    for (const auto& e : row.events) kinds.insert(e.kind);
  for (const auto& kind : kinds) legend.emplace_back(event_colour(kind), kind);
  s.html = "<p>" + std::to_string(count) + (count == 1 ? " event for " : " events for ") +
           std::to_string(users.size()) + (users.size() == 1 ? " user" : " users") + "; hover a dot for its score and view.</p>" + html_legend(legend) +
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
  const bool colour = std::any_of(run.reid.begin(), run.reid.end(), [](const ReidFrameRow& r) {
    return std::any_of(r.ms.begin(), r.ms.end(), [](const auto& stage) { return stage.first == "detect"; });
  });
  s.html = "<p>One row per tracked body (" + std::to_string(strips.size()) +
           " tracks), coloured by the user it was identified as in each frame." +
           (colour ? " Bodies from colour alone (the plain-camera pipeline: detector, tracker and body masks; "
                     "no depth, so no stature)."
                   : "") +
           "</p>" + html_legend(legend) +
           strip_timeline(strips, run.reid.front().frame, run.reid.back().frame + 1, "frame");
  return s;
}

// A live run (the rows carry "arrival"): frames dropped, and how long decisions took from the frame's
// arrival to its line being written, over the frames with events (what a person waits for) and all frames.
std::optional<Section> live_section(const RunData& run) {
  std::vector<double> with_events, all;
  long dropped = 0;
  int frames = 0;
  for (const auto& row : run.reid) {
    if (row.dropped) dropped = std::max(dropped, *row.dropped);
    if (row.end || !row.arrival || !row.wall) continue;
    ++frames;
    const double ms = (*row.wall - *row.arrival) * 1000.0;
    all.push_back(ms);
    if (!row.events.empty()) with_events.push_back(ms);
  }
  if (frames == 0) return std::nullopt;
  auto latency = [](const std::vector<double>& v) {
    return v.empty() ? std::string("–") : fmt(percentile(v, 50), 1) + " / " + fmt(percentile(v, 95), 1);
  };
  Section s{"live", "Live source", ""};
  s.html = "<p>Frames came from a live source (a sensor, a camera, or a file played at its own rate with "
           "<code>--realtime</code>). " + std::to_string(frames) + " frames processed, <b>" + std::to_string(dropped) +
           "</b> dropped because processing fell behind.</p>" +
           html_table({"latency from frame arrival to decision", "frames", "p50 / p95 ms"},
                      {{"frames with events", std::to_string(with_events.size()), latency(with_events)},
                       {"all frames", std::to_string(all.size()), latency(all)}});
  return s;
}

}  // namespace

void add_reid_sections(const ReportInput& input, std::vector<Section>& out) {
  if (auto live = live_section(input.run)) out.push_back(std::move(*live));
  out.push_back(events_section(input.run));
  out.push_back(identities_section(input.run));
  out.push_back(key_frames_section(input));
}

}  // namespace bodyrec::report
