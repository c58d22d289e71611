// Line and bar charts on cairo (see plot.hpp).
#include <legwork/render/plot.hpp>

#include "canvas.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace legwork::render {

using detail::Align;
using detail::text;

Rgb palette_color(int i) {
  // Tableau 10 without its blue and orange: those are the body's left and
  // right (kLeftColor, kRightColor), set explicitly by series that mean a side.
  static const Rgb kPalette[] = {{0.00, 0.47, 0.50}, {0.58, 0.40, 0.74}, {0.55, 0.34, 0.29}, {0.89, 0.47, 0.76},
                                 {0.50, 0.50, 0.50}, {0.74, 0.74, 0.13}, {0.84, 0.15, 0.16}, {0.09, 0.75, 0.81}};
  const int n = static_cast<int>(std::size(kPalette));
  return kPalette[((i % n) + n) % n];
}

namespace {

constexpr Rgb kInk{0.12, 0.12, 0.14};
constexpr Rgb kAxis{0.35, 0.35, 0.38};
constexpr Rgb kGridLine{0.9, 0.9, 0.92};

// A y-axis label read bottom to top, centred on (x, y); nothing when empty.
void y_axis_label(cairo_t* cr, double x, double y, const std::string& label) {
  if (label.empty()) return;
  cairo_save(cr);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, -kPi / 2);
  text(cr, 0, 0, label, 12, Align::Centre, kInk);
  cairo_restore(cr);
}

struct Range {
  double lo = 0, hi = 1, step = 0.2;
};

// Nice axis limits and tick step covering [lo, hi].
Range nice_range(double lo, double hi, int ticks, bool snap) {
  if (!(std::isfinite(lo) && std::isfinite(hi))) lo = 0, hi = 1;
  if (hi - lo < 1e-12) {
    const double pad = std::max(0.5, std::abs(lo) * 0.1);
    lo -= pad;
    hi += pad;
  }
  Range r;
  r.step = detail::nice_step(hi - lo, ticks);
  r.lo = snap ? std::floor(lo / r.step + 1e-9) * r.step : lo;
  r.hi = snap ? std::ceil(hi / r.step - 1e-9) * r.step : hi;
  return r;
}

// Decimals that show the tick step exactly (0.25 -> 2, 5 -> 0).
int decimals_for(double step) {
  int d = 0;
  while (d < 6 && std::abs(step * std::pow(10.0, d) - std::round(step * std::pow(10.0, d))) > 1e-6) ++d;
  return d;
}

struct LegendItem {
  std::string label;
  Rgb color;
  bool band = false;  // a filled swatch instead of a line
  bool dashed = false;
  double swatch_alpha = 0.3;
};

// Legend box size in pixels.
std::pair<double, double> legend_size(cairo_t* cr, const std::vector<LegendItem>& items) {
  double w = 0;
  for (const auto& it : items) w = std::max(w, detail::text_width(cr, it.label, 11));
  return {w + 40, 16.0 * static_cast<double>(items.size()) + 8};
}

// Legend box with its top-left corner at (x0, y0).
void draw_legend_at(cairo_t* cr, const std::vector<LegendItem>& items, double x0, double y0) {
  if (items.empty()) return;
  const auto [box_w, box_h] = legend_size(cr, items);
  const double row = 16;
  detail::layout_area(cr, x0, y0, box_w, box_h, true);
  cairo_save(cr);
  cairo_rectangle(cr, x0, y0, box_w, box_h);
  cairo_set_source_rgba(cr, 1, 1, 1, 0.88);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.82, 0.82, 0.85);
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
  for (std::size_t i = 0; i < items.size(); ++i) {
    const double y = y0 + 4 + row * static_cast<double>(i) + row / 2;
    const auto& it = items[i];
    if (it.band) {
      cairo_rectangle(cr, x0 + 8, y - 5, 20, 10);
      detail::set_color(cr, it.color, it.swatch_alpha);
      cairo_fill(cr);
    } else {
      cairo_move_to(cr, x0 + 8, y);
      cairo_line_to(cr, x0 + 28, y);
      detail::set_color(cr, it.color);
      cairo_set_line_width(cr, 2);
      if (it.dashed) {
        const double dash[] = {5, 3};
        cairo_set_dash(cr, dash, 2, 0);
      }
      cairo_stroke(cr);
      cairo_set_dash(cr, nullptr, 0, 0);
    }
    text(cr, x0 + 34, y + 4, it.label, 11, Align::Left, kInk);
  }
  cairo_restore(cr);
}

std::vector<LegendItem> panel_legend(const PlotPanel& p);

// A panel's drawing area and its value -> pixel mappings.
struct PanelFrame {
  Range xr, yr;
  double left = 0, top = 0, w = 0, h = 0;
  double X(double x) const { return left + (x - xr.lo) / (xr.hi - xr.lo) * w; }
  double Y(double y) const { return top + h - (y - yr.lo) / (yr.hi - yr.lo) * h; }
};

// y range from the data in the x range (and the reference lines) unless fixed.
Range panel_y_range(const PlotPanel& p, const Range& xr) {
  double ylo = INFINITY, yhi = -INFINITY;
  for (const auto& s : p.series)
    for (std::size_t i = 0; i < s.y.size(); ++i)
      if (std::isfinite(s.y[i]) && s.x[i] >= xr.lo && s.x[i] <= xr.hi) ylo = std::min(ylo, s.y[i]), yhi = std::max(yhi, s.y[i]);
  for (const auto& r : p.ref_lines) ylo = std::min(ylo, r.y), yhi = std::max(yhi, r.y);
  const bool fixed = std::isfinite(p.y_min) && std::isfinite(p.y_max);
  return fixed ? nice_range(p.y_min, p.y_max, 5, false) : nice_range(ylo, yhi, 5, true);
}

void draw_bands_and_grid(cairo_t* cr, const PlotPanel& p, const PanelFrame& f) {
  for (const auto& b : p.bands) {
    cairo_rectangle(cr, f.X(std::min(b.x0, b.x1)), f.top, std::abs(f.X(b.x1) - f.X(b.x0)), f.h);
    detail::set_color(cr, b.color, b.alpha);
    cairo_fill(cr);
  }
  cairo_set_line_width(cr, 1);
  detail::set_color(cr, kGridLine);
  for (double y = std::ceil(f.yr.lo / f.yr.step - 1e-9) * f.yr.step; y <= f.yr.hi + 1e-9 * f.yr.step; y += f.yr.step) {
    cairo_move_to(cr, f.left, std::round(f.Y(y)) + 0.5);
    cairo_line_to(cr, f.left + f.w, std::round(f.Y(y)) + 0.5);
  }
  for (double x = std::ceil(f.xr.lo / f.xr.step - 1e-9) * f.xr.step; x <= f.xr.hi + 1e-9 * f.xr.step; x += f.xr.step) {
    cairo_move_to(cr, std::round(f.X(x)) + 0.5, f.top);
    cairo_line_to(cr, std::round(f.X(x)) + 0.5, f.top + f.h);
  }
  cairo_stroke(cr);
}

void draw_reference_lines(cairo_t* cr, const PlotPanel& p, const PanelFrame& f) {
  for (const auto& r : p.ref_lines) {
    const double dash[] = {6, 4};
    cairo_set_dash(cr, dash, 2, 0);
    cairo_move_to(cr, f.left, f.Y(r.y));
    cairo_line_to(cr, f.left + f.w, f.Y(r.y));
    detail::set_color(cr, r.color);
    cairo_set_line_width(cr, 1.2);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    if (!r.label.empty()) {
      const double tw = detail::text_width(cr, r.label, 11);
      cairo_rectangle(cr, f.left + 6, f.Y(r.y) - 16, tw + 6, 13);
      cairo_set_source_rgba(cr, 1, 1, 1, 0.8);
      cairo_fill(cr);
      text(cr, f.left + 9, f.Y(r.y) - 5, r.label, 11, Align::Left, r.color);
    }
  }
}

void draw_curves(cairo_t* cr, const PlotPanel& p, const PanelFrame& f) {
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (std::size_t si = 0; si < p.series.size(); ++si) {
    const auto& s = p.series[si];
    bool pen = false;
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        pen = false;
        continue;
      }
      if (pen)
        cairo_line_to(cr, f.X(s.x[i]), f.Y(s.y[i]));
      else
        cairo_move_to(cr, f.X(s.x[i]), f.Y(s.y[i]));
      pen = true;
    }
    detail::set_color(cr, s.color.value_or(palette_color(static_cast<int>(si))));
    cairo_set_line_width(cr, s.width);
    if (s.dashed) {
      const double dash[] = {6, 4};
      cairo_set_dash(cr, dash, 2, 0);
    }
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
  }
}

// Frame, tick labels, axis labels and the panel title.
void draw_axes(cairo_t* cr, const PlotPanel& p, const PanelFrame& f, bool x_ticks, const std::string& x_label) {
  detail::set_color(cr, kAxis);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, std::round(f.left) + 0.5, std::round(f.top) + 0.5, std::round(f.w), std::round(f.h));
  cairo_stroke(cr);
  const int yd = decimals_for(f.yr.step), xd = decimals_for(f.xr.step);
  for (double y = std::ceil(f.yr.lo / f.yr.step - 1e-9) * f.yr.step; y <= f.yr.hi + 1e-9 * f.yr.step; y += f.yr.step)
    text(cr, f.left - 6, f.Y(y) + 4, detail::format_number(y, yd), 11, Align::Right, kAxis);
  if (x_ticks) {
    for (double x = std::ceil(f.xr.lo / f.xr.step - 1e-9) * f.xr.step; x <= f.xr.hi + 1e-9 * f.xr.step; x += f.xr.step)
      text(cr, f.X(x), f.top + f.h + 16, detail::format_number(x, xd), 11, Align::Centre, kAxis);
    text(cr, f.left + f.w / 2, f.top + f.h + 34, x_label, 12, Align::Centre, kInk);
  }
  // Rotated y label, centred on the panel.
  y_axis_label(cr, f.left - 48, f.top + f.h / 2, p.y_label);
  text(cr, f.left, f.top - 7, p.title, 12, Align::Left, kInk, 1.0, true);
}

void draw_panel(cairo_t* cr, const PlotPanel& p, const Range& xr, double left, double top, double w, double h,
                bool x_ticks, const std::string& x_label) {
  const PanelFrame f{xr, panel_y_range(p, xr), left, top, w, h};
  detail::layout_area(cr, left, top, w, h, false);
  cairo_save(cr);
  cairo_rectangle(cr, left, top, w, h);  // bands, grid and curves stay inside the panel
  cairo_clip(cr);
  draw_bands_and_grid(cr, p, f);
  draw_reference_lines(cr, p, f);
  draw_curves(cr, p, f);
  cairo_restore(cr);
  cairo_save(cr);
  draw_axes(cr, p, f, x_ticks, x_label);
  cairo_restore(cr);
  if (const auto items = panel_legend(p); !items.empty()) {
    // Outside the data: in the margin right of the panel (plot_lines reserves it).
    draw_legend_at(cr, items, left + w + 10, top);
  }
}

// A panel's legend entries: named series, then one entry per band label.
std::vector<LegendItem> panel_legend(const PlotPanel& p) {
  std::vector<LegendItem> items;
  if (!p.legend) return items;
  for (std::size_t si = 0; si < p.series.size(); ++si)
    if (!p.series[si].name.empty())
      items.push_back({p.series[si].name, p.series[si].color.value_or(palette_color(static_cast<int>(si))), false, p.series[si].dashed});
  std::set<std::string> seen;
  for (const auto& b : p.bands)
    if (!b.label.empty() && seen.insert(b.label).second) items.push_back({b.label, b.color, true, false});
  return items;
}

}  // namespace

void plot_lines(const LinePlot& plot, const std::string& path) {
  detail::format_of(path);
  if (plot.panels.empty()) throw Error("plot '" + path + "': no panels");
  double xlo = INFINITY, xhi = -INFINITY;
  for (std::size_t pi = 0; pi < plot.panels.size(); ++pi)
    for (const auto& s : plot.panels[pi].series) {
      if (s.x.size() != s.y.size())
        throw Error("plot '" + path + "': series '" + s.name + "' in panel " + std::to_string(pi) + " has " +
                    std::to_string(s.x.size()) + " x values but " + std::to_string(s.y.size()) + " y values");
      for (double x : s.x)
        if (std::isfinite(x)) xlo = std::min(xlo, x), xhi = std::max(xhi, x);
    }
  if (std::isfinite(plot.x_min)) xlo = plot.x_min;
  if (std::isfinite(plot.x_max)) xhi = plot.x_max;
  Range xr = nice_range(xlo, xhi, std::max(4, plot.width / 110), false);

  const double title_h = plot.title.empty() ? 8 : 36, panel_gap = 30, bottom = 50, left = 78;
  const int n = static_cast<int>(plot.panels.size());
  const int height = static_cast<int>(title_h + n * (plot.panel_height + panel_gap) + bottom - panel_gap + 20);
  // The right margin holds the widest panel legend (measured on a scratch surface).
  double legend_w = 0;
  {
    cairo_surface_t* scratch = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1);
    cairo_t* m = cairo_create(scratch);
    for (const auto& p : plot.panels)
      if (const auto items = panel_legend(p); !items.empty()) legend_w = std::max(legend_w, legend_size(m, items).first);
    cairo_destroy(m);
    cairo_surface_destroy(scratch);
  }
  const double right = 18, extra = legend_w > 0 ? legend_w + 14 : 0;  // the canvas grows by the legend column
  detail::Canvas canvas(path, plot.width + static_cast<int>(std::ceil(extra)), height);
  cairo_t* cr = canvas.cr();
  if (!plot.title.empty()) detail::title(cr, 12, 24, plot.title, 16, plot.width + extra - 24);
  for (int i = 0; i < n; ++i) {
    const double top = title_h + 20 + i * (plot.panel_height + panel_gap);
    draw_panel(cr, plot.panels[static_cast<std::size_t>(i)], xr, left, top, plot.width - left - right,
               plot.panel_height, i == n - 1, plot.x_label);
  }
  canvas.finish();
}

namespace {

// A scratch cairo context for measuring text before the canvas size is known.
struct Measure {
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1);
  cairo_t* cr = cairo_create(surface);
  ~Measure() {
    cairo_destroy(cr);
    cairo_surface_destroy(surface);
  }
};

constexpr double kValueSize = 11;  // value labels, legend and notes: never smaller

std::vector<LegendItem> bar_legend(const BarChart& chart) {
  std::vector<LegendItem> items;
  for (std::size_t s = 0; s < chart.series.size(); ++s)
    if (!chart.series[s].name.empty())
      items.push_back({chart.series[s].name, chart.series[s].color.value_or(palette_color(static_cast<int>(s))), true, false, 1.0});
  return items;
}

// Legend entries in rows across `width` from (x0, y0): returns the height used.
double legend_rows(cairo_t* cr, const std::vector<LegendItem>& items, double x0, double y0, double width, bool draw) {
  double x = x0, y = y0;
  for (const auto& it : items) {
    const double iw = detail::text_width(cr, it.label, kValueSize) + 42;
    if (x > x0 && x + iw > x0 + width) x = x0, y += 18;
    if (draw) {
      cairo_rectangle(cr, x, y + 3, 20, 10);
      detail::set_color(cr, it.color);
      cairo_fill(cr);
      text(cr, x + 26, y + 12, it.label, kValueSize, Align::Left, kInk);
    }
    x += iw;
  }
  return items.empty() ? 0 : y - y0 + 20;
}

// The canvas width that gives every bar room for its value label.
int bar_chart_width(const BarChart& chart, cairo_t* cr, double margins) {
  double label_w = detail::text_width(cr, "n/a", kValueSize);
  for (const auto& s : chart.series)
    for (double v : s.values)
      if (std::isfinite(v)) label_w = std::max(label_w, detail::text_width(cr, detail::format_number(v, chart.value_decimals), kValueSize));
  const double bars = static_cast<double>(chart.groups.size() * chart.series.size());
  const double needed = margins + (chart.show_values ? (label_w + 4) * bars / 0.78 : 0);
  return std::max(chart.width, static_cast<int>(std::ceil(needed)));
}

}  // namespace

void plot_bars(const BarChart& chart, const std::string& path) {
  detail::format_of(path);
  if (chart.groups.empty() || chart.series.empty()) throw Error("bar chart '" + path + "': no groups or no series");
  for (const auto& s : chart.series)
    if (s.values.size() != chart.groups.size())
      throw Error("bar chart '" + path + "': series '" + s.name + "' has " + std::to_string(s.values.size()) +
                  " values for " + std::to_string(chart.groups.size()) + " groups");
  double lo = 0, hi = 0;  // bars start at zero, so zero is always in range
  for (const auto& s : chart.series)
    for (double v : s.values)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (hi - lo < 1e-12) hi = lo + 1;
  const Range yr = nice_range(lo - (lo < 0 ? 0.08 * (hi - lo) : 0), hi + 0.08 * (hi - lo), 5, true);

  const double left = 78, right = 18;
  const auto items = bar_legend(chart);
  Measure m;
  const int width = bar_chart_width(chart, m.cr, left + right);
  const double w = width - left - right;
  // Title, then the legend in rows above the bars (never over them), bars, group labels, notes.
  const double legend_top = chart.title.empty() ? 8 : 36;
  const double title_h = legend_top + legend_rows(m.cr, items, left, legend_top, w, false) + 8;
  const double notes_h = chart.notes.empty() ? 0 : 10 + 16.0 * static_cast<double>(chart.notes.size());
  // The canvas is as high as asked unless that leaves the bars under 120 px.
  const double h = std::max(120.0, chart.height - title_h - 48 - notes_h);
  const int height = static_cast<int>(std::ceil(title_h + h + 48 + notes_h));
  detail::Canvas canvas(path, width, height);
  cairo_t* cr = canvas.cr();
  if (!chart.title.empty()) detail::title(cr, 12, 24, chart.title, 16, width - 24);
  if (!items.empty()) detail::layout_area(cr, left, legend_top, w, legend_rows(m.cr, items, left, legend_top, w, false), true);
  legend_rows(cr, items, left, legend_top, w, true);
  detail::layout_area(cr, left, title_h, w, h, false);
  auto Y = [&](double y) { return title_h + h - (y - yr.lo) / (yr.hi - yr.lo) * h; };
  const int yd = decimals_for(yr.step);
  cairo_set_line_width(cr, 1);
  for (double y = yr.lo; y <= yr.hi + 1e-9 * yr.step; y += yr.step) {
    detail::set_color(cr, kGridLine);
    cairo_move_to(cr, left, std::round(Y(y)) + 0.5);
    cairo_line_to(cr, left + w, std::round(Y(y)) + 0.5);
    cairo_stroke(cr);
    text(cr, left - 6, Y(y) + 4, detail::format_number(y, yd), 11, Align::Right, kAxis);
  }
  const auto groups = static_cast<double>(chart.groups.size());
  const auto per = static_cast<double>(chart.series.size());
  const double group_w = w / groups, bar_w = group_w * 0.78 / per;
  for (std::size_t g = 0; g < chart.groups.size(); ++g) {
    const double gx = left + group_w * static_cast<double>(g) + group_w * 0.11;
    for (std::size_t s = 0; s < chart.series.size(); ++s) {
      const double v = chart.series[s].values[g];
      const double x = gx + bar_w * static_cast<double>(s);
      if (!std::isfinite(v)) {
        text(cr, x + bar_w / 2, Y(0) - 4, "n/a", kValueSize, Align::Centre, kAxis);
        continue;
      }
      cairo_rectangle(cr, x + 1, std::min(Y(v), Y(0)), bar_w - 2, std::abs(Y(v) - Y(0)));
      detail::set_color(cr, chart.series[s].color.value_or(palette_color(static_cast<int>(s))));
      cairo_fill(cr);
      if (chart.show_values)
        text(cr, x + bar_w / 2, v >= 0 ? Y(v) - 4 : Y(v) + kValueSize + 3, detail::format_number(v, chart.value_decimals), kValueSize,
             Align::Centre, kInk);
    }
    text(cr, left + group_w * (static_cast<double>(g) + 0.5), title_h + h + 18, chart.groups[g], 12, Align::Centre, kInk);
  }
  // Zero line and frame.
  detail::set_color(cr, kAxis);
  cairo_move_to(cr, left, std::round(Y(0)) + 0.5);
  cairo_line_to(cr, left + w, std::round(Y(0)) + 0.5);
  cairo_stroke(cr);
  cairo_rectangle(cr, std::round(left) + 0.5, std::round(title_h) + 0.5, std::round(w), std::round(h));
  cairo_stroke(cr);
  y_axis_label(cr, left - 52, title_h + h / 2, chart.y_label);
  for (std::size_t i = 0; i < chart.notes.size(); ++i)
    text(cr, 12, title_h + h + 48 + 16.0 * static_cast<double>(i), chart.notes[i], kValueSize, Align::Left, kAxis);
  canvas.finish();
}

}  // namespace legwork::render
