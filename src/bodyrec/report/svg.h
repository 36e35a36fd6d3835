// Inline SVG plots drawn by our own code (no JavaScript, no external library): axes with ticks, line and
// step plots, bar charts, histograms, strip timelines and a polar rose. Each function returns one
// <svg> element that scales to the page width (viewBox, width 100%). Labels are HTML-escaped.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace bodyrec::report {

struct PlotFrame {
  int width = 760, height = 260;                       // viewBox size
  int left = 56, right = 16, top = 14, bottom = 44;    // margins for tick labels and axis titles
  std::string x_label, y_label;
};

// About `max_ticks` round tick values (1, 2, 5 x 10^k steps) covering [lo, hi].
std::vector<double> nice_ticks(double lo, double hi, int max_ticks = 6);

// A coordinate system inside a PlotFrame: data ranges to pixels, axes, grid, tick labels, axis titles.
class Axes {
 public:
  Axes(PlotFrame frame, double x0, double x1, double y0, double y1);
  double px(double x) const;
  double py(double y) const;
  // Grid lines, ticks and labels on both axes (x ticks skipped when `x_ticks` is false).
  std::string draw(bool x_ticks = true) const;
  const PlotFrame& frame() const { return f_; }

 private:
  PlotFrame f_;
  double x0_, x1_, y0_, y1_;
};

// Opens an <svg> with the viewBox of `frame` and a CSS class; close with "</svg>".
std::string svg_open(int width, int height, const std::string& css_class, const std::string& aria_label);

struct Series {
  std::string name, colour;
  std::vector<double> x, y;  // same length
  bool step = false;          // hold each value until the next x (counts per frame)
  bool markers = false;       // a dot at every point (few points, e.g. CMC ranks)
};

// Lines over a shared axis; y from 0 (or y_min) to the largest value (or y_max) with a little headroom.
std::string line_plot(const std::vector<Series>& series, const PlotFrame& frame,
                      std::optional<double> y_min = std::nullopt, std::optional<double> y_max = std::nullopt);

struct Bar {
  std::string label, colour;
  double value = 0;
  std::string note;  // shown above the bar (e.g. the value), "" = the value with 3 decimals
};

// Vertical bars, one per entry, labels under them, y from 0 to y_max (or the largest value).
std::string bar_chart(const std::vector<Bar>& bars, const PlotFrame& frame, std::optional<double> y_max = std::nullopt);

// Histogram of `values` with `bins` equal bins over [min, max] of the values (or [lo, hi] when given);
// the y axis counts values. Returns the counts through `counts` when non-null.
std::string histogram(const std::vector<double>& values, int bins, const PlotFrame& frame, const std::string& colour,
                      std::vector<int>* counts = nullptr);

// One row per labelled entity (a track, a body) along a shared x axis (frames); each segment is a
// coloured interval [begin, end) with a hover title. Rows are <g class="tl-row">.
struct Segment {
  double begin = 0, end = 0;
  std::string colour, title;
};
struct StripRow {
  std::string label;
  std::vector<Segment> segments;
};
std::string strip_timeline(const std::vector<StripRow>& rows, double x0, double x1, const std::string& x_label,
                           int row_height = 12);

// A polar histogram (rose): `weights[i]` is the weight of the sector centred on i * 360 / n degrees,
// 0 = right, 90 = up, counter-clockwise; petal radius ~ sqrt(weight) so areas compare honestly.
std::string polar_rose(const std::vector<double>& weights, const std::string& colour, int size = 340);

// Markers on rows: an event timeline. Each point has an x, a row index, a colour and a hover title.
struct EventPoint {
  double x = 0;
  int row = 0;
  std::string colour, title;
};
std::string event_timeline(const std::vector<EventPoint>& points, const std::vector<std::string>& row_labels,
                           double x0, double x1, const std::string& x_label);

}  // namespace bodyrec::report
