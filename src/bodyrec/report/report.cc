#include "bodyrec/report/report.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "bodyrec/report/html.h"
#include "bodyrec/report/sections.h"

namespace bodyrec::report {
namespace {

// Light palette, system sans-serif fonts (nothing fetched), responsive width, print-friendly.
const char* const kCss = R"css(
:root{--ink:#1e293b;--muted:#64748b;--line:#e2e8f0;--bg:#f8fafc;--card:#fff;--accent:#2563eb}
*{box-sizing:border-box}
body{margin:0;background:var(--bg);color:var(--ink);font:15px/1.5 system-ui,-apple-system,"Segoe UI",Roboto,"DejaVu Sans",Helvetica,Arial,sans-serif}
main{max-width:1100px;margin:0 auto;padding:24px 20px 48px}
header h1{margin:0 0 4px;font-size:26px}
header .meta{display:flex;flex-wrap:wrap;gap:6px 18px;color:var(--muted);font-size:14px}
header .meta b{color:var(--ink);font-weight:600}
.privacy{margin:14px 0 6px;padding:10px 14px;border-left:4px solid #f59e0b;background:#fffbeb;border-radius:6px;font-size:14px}
nav{margin:10px 0 0;font-size:14px}nav a{color:var(--accent);text-decoration:none;margin-right:14px}
section{background:var(--card);border:1px solid var(--line);border-radius:10px;padding:16px 20px;margin:18px 0;box-shadow:0 1px 2px rgba(15,23,42,.04)}
section h2{margin:0 0 6px;font-size:19px}section h3{font-size:16px;margin:18px 0 4px}
p{margin:4px 0 10px}.note{color:var(--muted);font-style:italic}
svg.plot{width:100%;height:auto;display:block;font-size:11px;fill:var(--ink)}
svg.rose{max-width:360px}
svg .grid{stroke:var(--line);stroke-width:1}svg .axis,svg .tick{stroke:#94a3b8;stroke-width:1}
svg text{fill:#475569}svg text.title{fill:var(--ink);font-size:12px;font-weight:600}svg text.value{font-size:11px;fill:var(--ink)}
svg .petal{fill-opacity:.75;stroke:#fff;stroke-width:1}
.legend{display:flex;flex-wrap:wrap;gap:4px 16px;font-size:13px;margin:4px 0 6px}
.legend i{display:inline-block;width:12px;height:12px;border-radius:3px;margin-right:6px;vertical-align:-1px}
.side{display:flex;flex-wrap:wrap;gap:16px;align-items:center}.side .rose{flex:0 1 360px}.side p{flex:1 1 280px}
.frames{display:grid;grid-template-columns:repeat(auto-fill,minmax(300px,1fr));gap:12px}
figure{margin:0}figure img{width:100%;border-radius:6px;display:block;border:1px solid var(--line)}
figcaption{font-size:12px;color:var(--muted);text-align:center;padding-top:2px}
.users{display:flex;flex-direction:column;gap:12px}
.user{display:grid;grid-template-columns:170px repeat(8,minmax(0,1fr));gap:4px 8px;align-items:start;padding-bottom:12px;border-bottom:1px solid var(--line)}
.user:last-child{border-bottom:0;padding-bottom:0}
.user .who{display:flex;flex-direction:column;font-size:12px;color:var(--muted);line-height:1.35;padding-top:4px}
.user .who b{font-size:16px;margin-bottom:2px;overflow-wrap:anywhere}.user .who time{display:block;color:var(--ink);font-variant-numeric:tabular-nums}
.view{min-width:0}
.view img,.view .slot{display:block;width:100%;height:auto;aspect-ratio:1/2;border-radius:6px}
.view img{object-fit:contain;background:#f1f5f9;border:1px solid var(--line)}
.view .slot{display:flex;align-items:center;justify-content:center;text-align:center;font-size:11px;color:#94a3b8;padding:4px}
.view .empty{border:2px dashed #cbd5e1}
.view .withheld{border:1px solid #cbd5e1;background:repeating-linear-gradient(135deg,#f1f5f9 0 8px,#e2e8f0 8px 16px);color:var(--muted)}
.view figcaption{font-weight:600;color:var(--ink);padding-top:3px}
.uevents{grid-column:2/-1;display:flex;flex-wrap:wrap;gap:4px 6px;font-size:12px;align-items:center;margin-top:2px}
.uevents .from,.uevents .more{color:var(--muted)}
.uevent{border:1px solid;border-left-width:4px;border-radius:4px;padding:0 6px;background:#fff}
.uevent time{color:var(--muted);margin-left:6px;font-variant-numeric:tabular-nums}
table{border-collapse:collapse;font-size:13px;margin:6px 0 10px;width:100%}
th,td{border-bottom:1px solid var(--line);padding:4px 8px;text-align:left;vertical-align:top}
th{background:#f1f5f9;font-weight:600}.num{text-align:right;font-variant-numeric:tabular-nums}
details summary{cursor:pointer;color:var(--accent);font-size:14px}
footer{color:var(--muted);font-size:12px;text-align:center}
)css";

std::vector<StageTimes> stage_times(const RunData& run) {
  std::vector<StageTimes> out;
  if (run.kind == RunKind::kGroups)
    for (const auto& r : run.groups) out.push_back(r.ms);
  else
    for (const auto& r : run.reid) out.push_back(r.ms);
  return out;
}

Section header(const ReportInput& input) {
  const RunData& run = input.run;
  std::set<int> tracks;
  double first = 0, last = 0;
  int first_frame = 0, last_frame = 0;
  if (run.kind == RunKind::kGroups) {
    for (const auto& r : run.groups)
      for (const auto& p : r.people) tracks.insert(p.id);
    first = run.groups.front().time, last = run.groups.back().time;
    first_frame = run.groups.front().frame, last_frame = run.groups.back().frame;
  } else {
    for (const auto& r : run.reid)
      for (const auto& b : r.bodies) tracks.insert(b.track);
    // The end row (finish()'s events) repeats the last time one frame later: the span is the frames'.
    const auto last_row = std::find_if(run.reid.rbegin(), run.reid.rend(), [](const ReidFrameRow& r) { return !r.end; });
    const ReidFrameRow& final_row = last_row == run.reid.rend() ? run.reid.back() : *last_row;
    first = run.reid.front().time, last = final_row.time;
    first_frame = run.reid.front().frame, last_frame = final_row.frame;
  }
  Section s{"header", "", ""};
  auto item = [](const std::string& k, const std::string& v) {
    return "<span>" + html_escape(k) + " <b>" + html_escape(v) + "</b></span>";
  };
  s.html = "<h1>bodyrec report: " + std::string(to_string(run.kind)) + " run</h1><div class=\"meta\">" +
           item("run", run.name) + (input.source.empty() ? "" : item("input", input.source)) +
           item("generated", input.generated) +
           item("frames", std::to_string(run.frame_count()) + " (" + std::to_string(first_frame) + "–" +
                              std::to_string(last_frame) + ", " + fmt(last - first, 1) + " s)") +
           item("tracks", std::to_string(tracks.size())) +
           (input.evals.empty() ? "" : item("evaluations", std::to_string(input.evals.size()))) + "</div>";
  s.html += input.images
                ? "<div class=\"privacy\"><b>Privacy:</b> this report embeds images of people (key frames and "
                  "gallery views) and their identities. Treat it as personal data: share it only with people "
                  "allowed to see them, and delete it when done. Build it with <code>--no-images</code> to leave "
                  "every person's pixels out.</div>"
                : "<div class=\"privacy\"><b>Privacy:</b> built with <code>--no-images</code>: no image of a "
                  "person is embedded; it still holds track and identity numbers.</div>";
  return s;
}

}  // namespace

std::string role_colour(const std::string& role) {
  if (role == "leader") return "#2563eb";
  if (role == "member") return "#16a34a";
  if (role == "non-member") return "#dc2626";
  if (role == "potential-member" || role == "potential member") return "#f59e0b";
  return "#94a3b8";
}

std::vector<Section> build_sections(const ReportInput& input) {
  std::vector<Section> out{header(input)};
  if (input.run.kind == RunKind::kGroups) add_groups_sections(input, out);
  if (input.have_gallery) out.push_back(users_section(input));
  if (input.run.kind == RunKind::kReid) add_reid_sections(input, out);
  add_speed_section(stage_times(input.run), out);
  add_eval_sections(input, out);
  return out;
}

std::string render_report(const ReportInput& input) {
  const auto sections = build_sections(input);
  std::string page =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
      "<meta name=\"viewport\" content=\"width=device-width,initial-scale=1\">"
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; style-src "
      "'unsafe-inline'\"><title>bodyrec report: " +
      html_escape(input.run.name) + "</title><style>" + kCss + "</style></head><body><main>";
  page += "<header>" + sections.front().html + "<nav>";
  for (size_t i = 1; i < sections.size(); ++i)
    page += "<a href=\"#" + sections[i].id + "\">" + html_escape(sections[i].title) + "</a>";
  page += "</nav></header>";
  for (size_t i = 1; i < sections.size(); ++i)
    page += "<section id=\"" + sections[i].id + "\"><h2>" + html_escape(sections[i].title) + "</h2>" +
            sections[i].html + "</section>";
  page += "<footer>bodyrec " BODYREC_VERSION " · self-contained page: no scripts, nothing loaded from the network"
          "</footer></main></body></html>\n";
  return page;
}

}  // namespace bodyrec::report
