// Evaluation and speed sections: the numbers behind the claims, drawn.
#include <algorithm>
#include <cmath>

#include "bodyrec/core/percentile.h"
#include "bodyrec/report/html.h"
#include "bodyrec/report/sections.h"
#include "bodyrec/report/svg.h"

namespace bodyrec::report {
namespace {

std::string value_text(const nlohmann::json& v) {
  if (v.is_number_float()) return fmt(v.get<double>(), std::fabs(v.get<double>()) >= 100 ? 1 : 4);
  if (v.is_string()) return v.get<std::string>();
  return v.dump();
}

// The most telling keys per kind, in order; the rest of the JSON goes to a details list.
std::vector<std::string> headline_keys(EvalKind kind) {
  switch (kind) {
    case EvalKind::kReid: return {"matcher", "rank1", "rank5", "rank10", "rank20", "map", "probes", "gallery", "ms_per_image"};
    case EvalKind::kReidStream: return {"accuracy", "splits", "merges", "frames", "ms_per_frame"};
    case EvalKind::kGroups: return {"scene", "pair_precision", "pair_recall", "pair_f1", "pairs"};
    case EvalKind::kLandmarks: return {"mean_px", "mean_rel_height", "p90_rel_height", "persons", "ms_per_person"};
    case EvalKind::kTrack: return {"mota", "motp", "idf1", "id_switches", "frames", "ms_per_frame"};
    case EvalKind::kDetect: return {"ap50", "precision", "recall", "frames", "ms_per_frame"};
    case EvalKind::kRoles: return {"accuracy", "accuracy_matched", "boxes", "frames", "ms_per_frame"};
    case EvalKind::kSegment: return {"mean_iou", "persons", "matched", "extra", "frames", "ms_per_frame"};
    case EvalKind::kLandmarkErrors: return {};
  }
  return {};
}

std::string summary_table(const std::vector<EvalResult>& evals) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& e : evals) {
    std::string figures;
    if (e.kind == EvalKind::kLandmarkErrors) {
      figures = std::to_string(e.errors_rel_height.size()) + " per-person errors";
    } else {
      for (const auto& key : headline_keys(e.kind))
        if (e.summary.contains(key)) {
          const auto& v = e.summary[key];
          if (v.is_object() || v.is_array()) continue;
          figures += (figures.empty() ? "" : " · ") + key + " " + value_text(v);
        }
    }
    rows.push_back({to_string(e.kind), e.name, figures});
  }
  return html_table({"evaluation", "file", "figures"}, rows, 9);
}

std::string cmc_plot(const std::vector<EvalResult>& evals) {
  std::vector<Series> series;
  std::vector<std::pair<std::string, std::string>> legend;
  size_t longest = 0;
  for (const auto& e : evals) {
    if (e.kind != EvalKind::kReid || e.cmc.empty()) continue;
    Series s;
    s.colour = palette(static_cast<int>(series.size()));
    s.name = e.summary.contains("matcher") ? value_text(e.summary["matcher"]) : e.name;
    s.markers = e.cmc.size() <= 50;
    for (size_t r = 0; r < e.cmc.size(); ++r) {
      s.x.push_back(static_cast<double>(r + 1));
      s.y.push_back(e.cmc[r]);
    }
    longest = std::max(longest, e.cmc.size());
    legend.emplace_back(s.colour, s.name + " (rank-1 " + fmt(e.cmc[0] * 100, 1) + " %)");
    series.push_back(std::move(s));
  }
  if (series.empty()) return "";
  PlotFrame frame;
  frame.x_label = "rank";
  frame.y_label = "matching rate";
  return "<h3>CMC curve</h3><p>Fraction of probes whose true identity is within the first k gallery matches (" +
         std::to_string(longest) + " ranks).</p>" + html_legend(legend) + line_plot(series, frame, 0.0, 1.0);
}

std::string pair_f1_bars(const std::vector<EvalResult>& evals) {
  std::vector<Bar> bars;
  for (const auto& e : evals) {
    if (e.kind != EvalKind::kGroups) continue;
    const std::string scene = e.summary.contains("scene") ? value_text(e.summary["scene"]) : e.name;
    bars.push_back({scene, palette(static_cast<int>(bars.size())), e.summary.value("pair_f1", 0.0), ""});
  }
  if (bars.empty()) return "";
  PlotFrame frame;
  frame.y_label = "pair F1";
  frame.height = 220;
  return "<h3>Group membership: pair F1 per scene</h3>" + bar_chart(bars, frame, 1.0);
}

std::string landmark_histograms(const std::vector<EvalResult>& evals) {
  std::string out;
  bool summary_only = false;
  for (const auto& e : evals) {
    summary_only |= e.kind == EvalKind::kLandmarks;
    if (e.kind != EvalKind::kLandmarkErrors || e.errors_rel_height.empty()) continue;
    PlotFrame frame;
    frame.x_label = "mean landmark error / box height";
    frame.y_label = "persons";
    frame.height = 220;
    std::vector<double> sorted = e.errors_rel_height;
    std::sort(sorted.begin(), sorted.end());
    out += "<h3>Landmark error per person: " + html_escape(e.name) + "</h3><p>" + std::to_string(sorted.size()) +
           " persons, median " + fmt(sorted[sorted.size() / 2], 4) + ", worst " + fmt(sorted.back(), 4) + ".</p>" +
           histogram(e.errors_rel_height, 20, frame, "#0d9488");
  }
  if (out.empty() && summary_only)
    out = "<p class=\"note\">Landmark histogram: give the per-person errors too "
          "(bodyrec eval landmarks ... --per-person errors.jsonl, then --eval errors.jsonl).</p>";
  return out;
}

}  // namespace

const char* palette(int index) {
  static const char* const colours[] = {"#2563eb", "#dc2626", "#16a34a", "#d97706", "#7c3aed",
                                        "#0891b2", "#db2777", "#65a30d", "#475569", "#ea580c"};
  const int n = sizeof colours / sizeof colours[0];
  return colours[((index % n) + n) % n];
}

void add_eval_sections(const ReportInput& input, std::vector<Section>& out) {
  if (input.evals.empty()) return;
  Section s{"evaluations", "Evaluations", ""};
  s.html = summary_table(input.evals) + cmc_plot(input.evals) + pair_f1_bars(input.evals) +
           landmark_histograms(input.evals);
  out.push_back(s);
}

void add_speed_section(const std::vector<StageTimes>& frames, std::vector<Section>& out) {
  std::vector<std::string> stages;
  for (const auto& f : frames)
    for (const auto& [stage, ms] : f)
      if (std::find(stages.begin(), stages.end(), stage) == stages.end()) stages.push_back(stage);
  if (stages.empty()) return;
  std::vector<std::vector<std::string>> rows;
  std::vector<Bar> bars;
  Series total{"all stages", "#334155", {}, {}, false, false};
  std::vector<double> totals;
  for (size_t i = 0; i < frames.size(); ++i) {
    double sum = 0;
    for (const auto& [stage, ms] : frames[i]) sum += ms;
    total.x.push_back(static_cast<double>(i));
    total.y.push_back(sum);
    totals.push_back(sum);
  }
  auto p95 = [](const std::vector<double>& v) { return percentile(v, 95); };
  for (const auto& stage : stages) {
    std::vector<double> values;
    for (const auto& f : frames)
      for (const auto& [name, ms] : f)
        if (name == stage) values.push_back(ms);
    double mean = 0;
    for (double v : values) mean += v;
    mean /= std::max<size_t>(1, values.size());
    rows.push_back({stage, fmt(mean, 2), fmt(p95(values), 2), fmt(*std::max_element(values.begin(), values.end()), 2)});
    bars.push_back({stage, palette(static_cast<int>(bars.size())), mean, fmt(mean, 2) + " ms"});
  }
  double mean_total = 0;
  for (double v : totals) mean_total += v;
  mean_total /= std::max<size_t>(1, totals.size());
  rows.push_back({"all listed stages", fmt(mean_total, 2), fmt(p95(totals), 2),
                  fmt(*std::max_element(totals.begin(), totals.end()), 2)});
  PlotFrame bar_frame;
  bar_frame.y_label = "mean ms per frame";
  bar_frame.height = 200;
  PlotFrame line_frame;
  line_frame.x_label = "row of the run";
  line_frame.y_label = "ms (listed stages)";
  line_frame.height = 200;
  Section s{"speed", "Speed", ""};
  s.html = "<p>Milliseconds per frame of the stages the run timed (" + std::to_string(frames.size()) +
           " frames; stages not listed, such as detection and tracking, are not included).</p>" +
           html_table({"stage", "mean ms", "p95 ms", "max ms"}, rows) + bar_chart(bars, bar_frame) +
           line_plot({total}, line_frame);
  out.push_back(s);
}

}  // namespace bodyrec::report
