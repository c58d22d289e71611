#pragma once
// Small charts on cairo, for reports: stacked time-series panels (several
// named curves, shaded phase bands, reference lines, ticks, legend) and
// grouped bar charts with labelled values. Writes .png or .svg (by
// extension). Offline/tool code: allocates and throws legwork::Error on bad
// input (mismatched lengths, unknown extension, unwritable path).
//
//   render::LinePlot p;
//   p.title = "Ankle height"; p.x_label = "time (s)";
//   auto& panel = p.panels.emplace_back();
//   panel.y_label = "height (m)";
//   panel.series.push_back({"left", t, left_h});
//   panel.series.push_back({"right", t, right_h});
//   panel.bands.push_back({0.4, 0.9, render::kLeftColor, "left swing"});
//   render::plot_lines(p, "ankles.png");
#include <legwork/render/render.hpp>

#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace legwork::render {

// The default colour of the i-th curve or bar series (an 8-colour palette
// that prints and reads well, without the body's left blue and right orange,
// which series meaning a side set themselves; wraps around).
Rgb palette_color(int i);

// One named curve: y over x (same length). Non-finite y values break the line.
struct Series {
  std::string name;  // legend entry; empty = not in the legend
  std::vector<double> x, y;
  std::optional<Rgb> color;  // default: palette_color(index in its panel)
  double width = 1.8;        // pixels
  bool dashed = false;

  Series() = default;
  Series(std::string name_, std::vector<double> x_, std::vector<double> y_, std::optional<Rgb> color_ = std::nullopt)
      : name(std::move(name_)), x(std::move(x_)), y(std::move(y_)), color(color_) {}
};

// A shaded x interval, e.g. a gait phase; bands with the same label share one
// legend entry.
struct Band {
  double x0 = 0, x1 = 0;
  Rgb color{0.6, 0.6, 0.6};
  std::string label;
  double alpha = 0.15;

  Band() = default;
  Band(double x0_, double x1_, Rgb color_, std::string label_ = "", double alpha_ = 0.15)
      : x0(x0_), x1(x1_), color(color_), label(std::move(label_)), alpha(alpha_) {}
};

// A horizontal reference line (e.g. a threshold), labelled at the right end.
struct RefLine {
  double y = 0;
  std::string label;
  Rgb color{0.4, 0.4, 0.45};

  RefLine() = default;
  RefLine(double y_, std::string label_ = "", Rgb color_ = {0.4, 0.4, 0.45})
      : y(y_), label(std::move(label_)), color(color_) {}
};

// One panel of a LinePlot (its own y axis).
struct PlotPanel {
  std::string title;  // drawn above the panel, left
  std::string y_label;
  std::vector<Series> series;
  std::vector<Band> bands;
  std::vector<RefLine> ref_lines;
  // Fixed y range; NaN = fit the data (with nice tick limits).
  double y_min = std::numeric_limits<double>::quiet_NaN();
  double y_max = std::numeric_limits<double>::quiet_NaN();
  bool legend = true;
};

// Panels stacked vertically over one shared x axis (ticks on the bottom one).
struct LinePlot {
  std::string title;
  std::string x_label;
  std::vector<PlotPanel> panels;
  int width = 900;         // pixels
  int panel_height = 220;  // pixels per panel
  // Fixed x range; NaN = the data's extent.
  double x_min = std::numeric_limits<double>::quiet_NaN();
  double x_max = std::numeric_limits<double>::quiet_NaN();
};
void plot_lines(const LinePlot& plot, const std::string& path);

// One bar per group for each series (e.g. "ours" vs "baseline" per metric).
struct BarSeries {
  std::string name;
  std::vector<double> values;  // one per group; NaN = no bar ("n/a")
  std::optional<Rgb> color;    // default: palette_color(series index)

  BarSeries() = default;
  BarSeries(std::string name_, std::vector<double> values_, std::optional<Rgb> color_ = std::nullopt)
      : name(std::move(name_)), values(std::move(values_)), color(color_) {}
};

struct BarChart {
  std::string title;
  std::string y_label;
  std::vector<std::string> groups;  // category labels along x
  std::vector<BarSeries> series;
  int width = 800, height = 420;  // pixels; widened so that value labels fit their bars
  bool show_values = true;        // value printed on each bar (11 px)
  int value_decimals = 2;
  // Lines printed under the chart, e.g. what each group's short name means.
  std::vector<std::string> notes;
};
void plot_bars(const BarChart& chart, const std::string& path);

// Stacks PNG images vertically into one PNG (centred, white background);
// throws legwork::Error naming an unreadable part or an unwritable output.
void stack_pngs(const std::vector<std::string>& parts, const std::string& out);

}  // namespace legwork::render
