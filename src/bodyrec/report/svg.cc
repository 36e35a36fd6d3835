#include "bodyrec/report/svg.h"

#include <algorithm>
#include <cmath>

#include "bodyrec/report/html.h"

namespace bodyrec::report {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string num(double v) { return fmt(v, 1); }

std::string tick_label(double v) {
  if (std::fabs(v) >= 1000 || std::fabs(v - std::round(v)) < 1e-9) return fmt(v, 0);
  if (std::fabs(v * 10 - std::round(v * 10)) < 1e-9) return fmt(v, 1);
  return fmt(v, 2);
}

std::string text(double x, double y, const std::string& s, const std::string& anchor, const std::string& extra = "") {
  return "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" text-anchor=\"" + anchor + "\"" + extra + ">" +
         html_escape(s) + "</text>";
}

double top_of(double largest) { return largest > 0 ? largest * 1.08 : 1.0; }

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int max_ticks) {
  if (!(hi > lo)) return {lo};
  const double raw = (hi - lo) / std::max(1, max_ticks);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * mag;
    if (step >= raw) break;
  }
  std::vector<double> ticks;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step)
    ticks.push_back(std::fabs(t) < step * 1e-9 ? 0.0 : t);
  return ticks;
}

Axes::Axes(PlotFrame frame, double x0, double x1, double y0, double y1)
    : f_(std::move(frame)), x0_(x0), x1_(x1 > x0 ? x1 : x0 + 1), y0_(y0), y1_(y1 > y0 ? y1 : y0 + 1) {}

double Axes::px(double x) const { return f_.left + (x - x0_) / (x1_ - x0_) * (f_.width - f_.left - f_.right); }
double Axes::py(double y) const {
  return f_.height - f_.bottom - (y - y0_) / (y1_ - y0_) * (f_.height - f_.top - f_.bottom);
}

std::string Axes::draw(bool x_ticks) const {
  std::string out = "<g class=\"axes\">";
  for (double t : nice_ticks(y0_, y1_, 5)) {
    out += "<line class=\"grid\" x1=\"" + num(f_.left) + "\" x2=\"" + num(f_.width - f_.right) + "\" y1=\"" +
           num(py(t)) + "\" y2=\"" + num(py(t)) + "\"/>";
    out += text(f_.left - 6, py(t) + 4, tick_label(t), "end");
  }
  if (x_ticks)
    for (double t : nice_ticks(x0_, x1_, 8)) {
      out += "<line class=\"tick\" x1=\"" + num(px(t)) + "\" x2=\"" + num(px(t)) + "\" y1=\"" +
             num(f_.height - f_.bottom) + "\" y2=\"" + num(f_.height - f_.bottom + 4) + "\"/>";
      out += text(px(t), f_.height - f_.bottom + 16, tick_label(t), "middle");
    }
  out += "<line class=\"axis\" x1=\"" + num(f_.left) + "\" x2=\"" + num(f_.width - f_.right) + "\" y1=\"" +
         num(f_.height - f_.bottom) + "\" y2=\"" + num(f_.height - f_.bottom) + "\"/>";
  out += "<line class=\"axis\" x1=\"" + num(f_.left) + "\" x2=\"" + num(f_.left) + "\" y1=\"" + num(f_.top) +
         "\" y2=\"" + num(f_.height - f_.bottom) + "\"/>";
  if (!f_.x_label.empty())
    out += text((f_.left + f_.width - f_.right) / 2.0, f_.height - 6, f_.x_label, "middle", " class=\"title\"");
  if (!f_.y_label.empty()) {
    const double cy = (f_.top + f_.height - f_.bottom) / 2.0;
    out += text(14, cy, f_.y_label, "middle", " class=\"title\" transform=\"rotate(-90 14 " + num(cy) + ")\"");
  }
  return out + "</g>";
}

std::string svg_open(int width, int height, const std::string& css_class, const std::string& aria_label) {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"" + html_escape(css_class) + "\" viewBox=\"0 0 " +
         std::to_string(width) + " " + std::to_string(height) + "\" role=\"img\" aria-label=\"" +
         html_escape(aria_label) + "\">";
}

std::string line_plot(const std::vector<Series>& series, const PlotFrame& frame, std::optional<double> y_min,
                      std::optional<double> y_max) {
  double x0 = 0, x1 = 1, largest = 0;
  bool first = true;
  for (const auto& s : series)
    for (size_t i = 0; i < s.x.size(); ++i) {
      x0 = first ? s.x[i] : std::min(x0, s.x[i]);
      x1 = first ? s.x[i] : std::max(x1, s.x[i]);
      largest = std::max(largest, s.y[i]);
      first = false;
    }
  const Axes axes(frame, x0, x1, y_min.value_or(0.0), y_max.value_or(top_of(largest)));
  std::string out = svg_open(frame.width, frame.height, "plot line-plot", frame.y_label) + axes.draw();
  for (const auto& s : series) {
    std::string points;
    for (size_t i = 0; i < s.x.size(); ++i) {
      if (s.step && i > 0) points += num(axes.px(s.x[i])) + "," + num(axes.py(s.y[i - 1])) + " ";
      points += num(axes.px(s.x[i])) + "," + num(axes.py(s.y[i])) + " ";
    }
    out += "<polyline class=\"series\" fill=\"none\" stroke=\"" + html_escape(s.colour) +
           "\" stroke-width=\"2\" points=\"" + points + "\"><title>" + html_escape(s.name) + "</title></polyline>";
    if (s.markers)
      for (size_t i = 0; i < s.x.size(); ++i)
        out += "<circle class=\"point\" cx=\"" + num(axes.px(s.x[i])) + "\" cy=\"" + num(axes.py(s.y[i])) +
               "\" r=\"3\" fill=\"" + html_escape(s.colour) + "\"><title>" + html_escape(s.name) + ": " +
               tick_label(s.x[i]) + " → " + fmt(s.y[i], 3) + "</title></circle>";
  }
  return out + "</svg>";
}

std::string bar_chart(const std::vector<Bar>& bars, const PlotFrame& frame, std::optional<double> y_max) {
  double largest = 0;
  for (const auto& b : bars) largest = std::max(largest, b.value);
  const int n = std::max<int>(1, static_cast<int>(bars.size()));
  const Axes axes(frame, 0, n, 0, y_max.value_or(top_of(largest)));
  std::string out = svg_open(frame.width, frame.height, "plot bar-chart", frame.y_label) + axes.draw(false);
  const double slot = axes.px(1) - axes.px(0), width = std::min(slot * 0.7, 90.0);
  for (int i = 0; i < static_cast<int>(bars.size()); ++i) {
    const Bar& b = bars[i];
    const double cx = axes.px(i + 0.5), top = axes.py(b.value), base = axes.py(0);
    out += "<rect class=\"bar\" x=\"" + num(cx - width / 2) + "\" y=\"" + num(top) + "\" width=\"" + num(width) +
           "\" height=\"" + num(std::max(0.0, base - top)) + "\" fill=\"" + html_escape(b.colour) + "\"><title>" +
           html_escape(b.label) + ": " + fmt(b.value, 3) + "</title></rect>";
    out += text(cx, top - 4, b.note.empty() ? fmt(b.value, 3) : b.note, "middle", " class=\"value\"");
    out += text(cx, frame.height - frame.bottom + 16, b.label, "middle");
  }
  return out + "</svg>";
}

std::string histogram(const std::vector<double>& values, int bins, const PlotFrame& frame, const std::string& colour,
                      std::vector<int>* counts_out) {
  bins = std::max(1, bins);
  double lo = 0, hi = 1;
  if (!values.empty()) {
    lo = *std::min_element(values.begin(), values.end());
    hi = *std::max_element(values.begin(), values.end());
  }
  if (!(hi > lo)) hi = lo + 1;
  std::vector<int> counts(bins, 0);
  for (double v : values) counts[std::min(bins - 1, static_cast<int>((v - lo) / (hi - lo) * bins))]++;
  const int largest = counts.empty() ? 0 : *std::max_element(counts.begin(), counts.end());
  const Axes axes(frame, lo, hi, 0, top_of(largest));
  std::string out = svg_open(frame.width, frame.height, "plot histogram", frame.y_label) + axes.draw();
  const double w = (hi - lo) / bins;
  for (int i = 0; i < bins; ++i) {
    const double x = axes.px(lo + i * w), x2 = axes.px(lo + (i + 1) * w), top = axes.py(counts[i]);
    out += "<rect class=\"bin\" x=\"" + num(x + 0.5) + "\" y=\"" + num(top) + "\" width=\"" +
           num(std::max(0.5, x2 - x - 1)) + "\" height=\"" + num(axes.py(0) - top) + "\" fill=\"" +
           html_escape(colour) + "\"><title>" + fmt(lo + i * w, 3) + " – " + fmt(lo + (i + 1) * w, 3) + ": " +
           std::to_string(counts[i]) + "</title></rect>";
  }
  if (counts_out) *counts_out = counts;
  return out + "</svg>";
}

std::string strip_timeline(const std::vector<StripRow>& rows, double x0, double x1, const std::string& x_label,
                           int row_height) {
  PlotFrame frame;
  frame.left = 64;
  frame.top = 6;
  frame.x_label = x_label;
  frame.height = frame.top + frame.bottom + row_height * std::max<int>(1, static_cast<int>(rows.size()));
  const Axes axes(frame, x0, x1, 0, std::max<int>(1, static_cast<int>(rows.size())));
  std::string out = svg_open(frame.width, frame.height, "plot timeline", x_label);
  out += "<g class=\"axes\">";
  for (double t : nice_ticks(x0, x1, 8)) {
    out += "<line class=\"grid\" x1=\"" + num(axes.px(t)) + "\" x2=\"" + num(axes.px(t)) + "\" y1=\"" +
           num(frame.top) + "\" y2=\"" + num(frame.height - frame.bottom) + "\"/>";
    out += text(axes.px(t), frame.height - frame.bottom + 16, tick_label(t), "middle");
  }
  out += text((frame.left + frame.width - frame.right) / 2.0, frame.height - 6, x_label, "middle",
              " class=\"title\"") + "</g>";
  const int label_size = std::min(11, row_height - 1);
  for (size_t r = 0; r < rows.size(); ++r) {
    const double y = frame.top + r * row_height;
    out += "<g class=\"tl-row\">";
    out += text(frame.left - 6, y + row_height * 0.5 + label_size * 0.35, rows[r].label, "end",
                " font-size=\"" + std::to_string(label_size) + "\"");
    for (const auto& s : rows[r].segments) {
      const double a = axes.px(s.begin), b = axes.px(s.end);
      out += "<rect x=\"" + num(a) + "\" y=\"" + num(y + 1) + "\" width=\"" + fmt(std::max(0.6, b - a), 2) +
             "\" height=\"" + num(row_height - 2) + "\" fill=\"" + html_escape(s.colour) + "\"><title>" +
             html_escape(s.title) + "</title></rect>";
    }
    out += "</g>";
  }
  return out + "</svg>";
}

std::string polar_rose(const std::vector<double>& weights, const std::string& colour, int size) {
  const double c = size / 2.0, radius = size / 2.0 - 54;  // room for the labels outside the circle
  std::string out = svg_open(size, size, "plot rose", "direction rose");
  double largest = 0;
  for (double w : weights) largest = std::max(largest, w);
  for (double f : {0.25, 0.5, 0.75, 1.0})
    out += "<circle class=\"grid\" cx=\"" + num(c) + "\" cy=\"" + num(c) + "\" r=\"" + num(radius * f) +
           "\" fill=\"none\"/>";
  const char* names[] = {"right 0°", "up 90°", "left 180°", "down 270°"};
  for (int k = 0; k < 4; ++k) {
    const double a = k * kPi / 2;
    out += "<line class=\"grid\" x1=\"" + num(c) + "\" y1=\"" + num(c) + "\" x2=\"" + num(c + radius * std::cos(a)) +
           "\" y2=\"" + num(c - radius * std::sin(a)) + "\"/>";
    const double lx = c + (radius + 6) * std::cos(a), ly = c - (radius + 8) * std::sin(a) + (k == 3 ? 10 : k == 1 ? 0 : 4);
    out += text(lx, ly, names[k], k == 0 ? "start" : k == 2 ? "end" : "middle");
  }
  const int n = static_cast<int>(weights.size());
  for (int i = 0; i < n && largest > 0; ++i) {
    if (weights[i] <= 0) continue;
    const double r = radius * std::sqrt(weights[i] / largest);
    const double a0 = (i - 0.5) * 2 * kPi / n, a1 = (i + 0.5) * 2 * kPi / n;
    out += "<path class=\"petal\" d=\"M" + num(c) + "," + num(c) + " L" + num(c + r * std::cos(a0)) + "," +
           num(c - r * std::sin(a0)) + " A" + num(r) + "," + num(r) + " 0 0 0 " + num(c + r * std::cos(a1)) + "," +
           num(c - r * std::sin(a1)) + " Z\" fill=\"" + html_escape(colour) + "\"><title>" +
           fmt(i * 360.0 / n, 0) + "°: " + fmt(weights[i], 2) + "</title></path>";
  }
  return out + "</svg>";
}

std::string event_timeline(const std::vector<EventPoint>& points, const std::vector<std::string>& row_labels,
                           double x0, double x1, const std::string& x_label) {
  const int row_height = 18;
  PlotFrame frame;
  frame.left = 72;
  frame.top = 6;
  frame.x_label = x_label;
  frame.height = frame.top + frame.bottom + row_height * std::max<int>(1, static_cast<int>(row_labels.size()));
  const Axes axes(frame, x0, x1, 0, 1);
  std::string out = svg_open(frame.width, frame.height, "plot events", x_label) + "<g class=\"axes\">";
  for (double t : nice_ticks(x0, x1, 8)) {
    out += "<line class=\"grid\" x1=\"" + num(axes.px(t)) + "\" x2=\"" + num(axes.px(t)) + "\" y1=\"" +
           num(frame.top) + "\" y2=\"" + num(frame.height - frame.bottom) + "\"/>";
    out += text(axes.px(t), frame.height - frame.bottom + 16, tick_label(t), "middle");
  }
  out += text((frame.left + frame.width - frame.right) / 2.0, frame.height - 6, x_label, "middle",
              " class=\"title\"");
  for (size_t r = 0; r < row_labels.size(); ++r) {
    const double y = frame.top + (r + 0.5) * row_height;
    out += "<line class=\"grid\" x1=\"" + num(frame.left) + "\" x2=\"" + num(frame.width - frame.right) +
           "\" y1=\"" + num(y) + "\" y2=\"" + num(y) + "\"/>";
    out += text(frame.left - 6, y + 4, row_labels[r], "end");
  }
  out += "</g>";
  for (const auto& p : points)
    out += "<circle class=\"event\" cx=\"" + num(axes.px(p.x)) + "\" cy=\"" +
           num(frame.top + (p.row + 0.5) * row_height) + "\" r=\"5\" fill=\"" + html_escape(p.colour) +
           "\"><title>" + html_escape(p.title) + "</title></circle>";
  return out + "</svg>";
}

}  // namespace bodyrec::report
