// Chart helper tests: files decode at the requested width, curves sit at the
// right height, bands on the right x interval, bars scale with their values,
// and bad input is a clear error.
#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/render/plot.hpp>

#include "render_test_util.hpp"
#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <fstream>
#include <sstream>

using namespace legwork;
using namespace legwork::render;
using legwork::render::testing::Image;
using legwork::render::testing::near_color;
using legwork::render::testing::out_dir;

namespace {
struct Stats {
  int n = 0;
  double mean_x = 0, mean_y = 0;
};
Stats pixels_of(const Image& img, const Rgb& c, double tol = 0.06) {
  Stats s;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      if (near_color(img.at(x, y), c, tol)) s.n++, s.mean_x += x, s.mean_y += y;
  if (s.n) s.mean_x /= s.n, s.mean_y /= s.n;
  return s;
}
}  // namespace

TEST(PlotLines, CurvesAtTheirHeightsAndBandsOnTheirInterval) {
  LinePlot p;
  p.title = "two levels";
  p.x_label = "x";
  p.width = 600;
  auto& panel = p.panels.emplace_back();
  panel.y_min = 0;
  panel.y_max = 1;
  panel.series.push_back({"low", {0, 1}, {0.2, 0.2}, Rgb{0.9, 0.1, 0.1}});
  panel.series.push_back({"high", {0, 1}, {0.8, 0.8}, Rgb{0.1, 0.1, 0.9}});
  for (auto& s : panel.series) s.width = 4;  // solid pixels despite anti-aliasing
  panel.bands.push_back({0.0, 0.3, Rgb{0.0, 0.8, 0.0}, "band", 0.5});
  panel.legend = false;  // keep legend swatches out of the pixel counts
  const auto file = (out_dir() / "plot_levels.png").string();
  plot_lines(p, file);
  Image img(file);
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img.width(), 600);
  const auto low = pixels_of(img, {0.9, 0.1, 0.1}), high = pixels_of(img, {0.1, 0.1, 0.9});
  ASSERT_GT(low.n, 200);
  ASSERT_GT(high.n, 200);
  EXPECT_GT(low.mean_y, high.mean_y + 50);  // 0.2 is drawn below 0.8
  // The band (green at alpha 0.5 over white) lies on the left part of the x range.
  const auto band = pixels_of(img, {0.5, 0.9, 0.5}, 0.06);
  ASSERT_GT(band.n, 500);
  EXPECT_LT(band.mean_x, 0.4 * img.width());
}

TEST(PlotLines, AnkleHeightsOfARealWalk) {
  const Motion m = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  const auto pos = joint_positions(m);
  const auto nj = static_cast<std::size_t>(m.joint_count());
  const auto la = static_cast<std::size_t>(m.skeleton.roles[Role::LeftAnkle]);
  const auto ra = static_cast<std::size_t>(m.skeleton.roles[Role::RightAnkle]);
  Series left("left ankle", {}, {}), right("right ankle", {}, {});
  left.color = kLeftColor;
  right.color = kRightColor;
  PlotPanel panel;
  panel.y_label = "height (m)";
  for (int f = 0; f < m.frame_count(); ++f) {
    const double t = f / m.fps;
    const auto fu = static_cast<std::size_t>(f);
    left.x.push_back(t);
    left.y.push_back(pos[fu * nj + la].y());
    right.x.push_back(t);
    right.y.push_back(pos[fu * nj + ra].y());
  }
  panel.series = {left, right};
  panel.ref_lines.push_back({0.12, "contact threshold"});
  LinePlot p;
  p.title = "07_01 ankle heights";
  p.x_label = "time (s)";
  p.panels = {panel, panel};
  p.panels[1].title = "same, as SVG check";
  const auto png = (out_dir() / "plot_ankles.png").string(), svg = (out_dir() / "plot_ankles.svg").string();
  plot_lines(p, png);
  plot_lines(p, svg);
  Image img(png);
  ASSERT_TRUE(img.ok());
  EXPECT_GT(pixels_of(img, kLeftColor).n, 300);
  EXPECT_GT(pixels_of(img, kRightColor).n, 300);
  std::ifstream in(svg);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("<path"), std::string::npos);
}

TEST(PlotBars, BarHeightsFollowValues) {
  BarChart c;
  c.title = "bars";
  c.groups = {"a", "b"};
  c.series.push_back({"s", {1.0, 3.0}, Rgb{0.2, 0.6, 0.2}});
  c.show_values = true;
  const auto file = (out_dir() / "plot_bars.png").string();
  plot_bars(c, file);
  Image img(file);
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img.width(), 800);
  EXPECT_EQ(img.height(), 420);
  // Pixels of the bar colour in the left and right halves (excluding the legend corner).
  int left = 0, right = 0;
  for (int y = 60; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      if (near_color(img.at(x, y), {0.2, 0.6, 0.2}, 0.05)) (x < img.width() / 2 ? left : right)++;
  ASSERT_GT(left, 100);
  EXPECT_NEAR(static_cast<double>(right) / left, 3.0, 0.35);
}

TEST(PlotLines, LegendStaysOutsideTheData) {
  // Curves near the top and bottom edges across the whole x range: a legend
  // in any corner of the panel would hide part of one (it used to).
  PlotPanel panel;
  panel.series.push_back({"top", {0, 10}, {0.9, 0.9}, Rgb{0.2, 0.6, 0.2}});
  panel.series.push_back({"bottom", {0, 10}, {0.1, 0.1}, Rgb{0.6, 0.2, 0.6}});
  for (auto& se : panel.series) se.width = 3;  // solid pixels of the exact colour
  panel.y_min = 0;
  panel.y_max = 1;
  LinePlot p;
  p.width = 600;
  p.panels = {panel};
  const auto file = (out_dir() / "plot_legend_outside.png").string();
  plot_lines(p, file);
  Image img(file);
  ASSERT_TRUE(img.ok());
  EXPECT_GT(img.width(), p.width) << "the legend column widens the canvas";
  // Every pixel column of the data area (x = 78 .. width - 18) shows both curves.
  int missing = 0;
  for (int x = 82; x < p.width - 22; ++x) {
    bool top = false, bottom = false;
    for (int y = 0; y < img.height(); ++y) {
      top = top || near_color(img.at(x, y), {0.2, 0.6, 0.2}, 0.05);
      bottom = bottom || near_color(img.at(x, y), {0.6, 0.2, 0.6}, 0.05);
    }
    missing += !top || !bottom;
  }
  EXPECT_EQ(missing, 0) << "pixel columns where a curve is hidden";
}

TEST(Plot, BadInputIsAClearError) {
  LinePlot p;
  EXPECT_THROW(plot_lines(p, (out_dir() / "empty.png").string()), Error);
  p.panels.emplace_back().series.push_back({"bad", {0, 1, 2}, {0, 1}});
  try {
    plot_lines(p, (out_dir() / "bad.png").string());
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad"), std::string::npos);
  }
  BarChart c;
  c.groups = {"a"};
  c.series.push_back({"s", {1.0, 2.0}});
  EXPECT_THROW(plot_bars(c, (out_dir() / "bars.png").string()), Error);
  c.series[0].values = {1.0};
  EXPECT_THROW(plot_bars(c, (out_dir() / "bars.bmp").string()), Error);
}
