// Layout recording: the chart layer reports where it put every text, panel
// and legend, and layout_problems() finds overlaps a reader would see. The
// real charts (ankle heights of a CMU walk, per-side bars) have none; faults
// made on purpose are found and named.
#include <legwork/core/fk.hpp>
#include <legwork/render/layout.hpp>
#include <legwork/render/plot.hpp>

#include "cmu_sample.hpp"
#include "render_test_util.hpp"

#include <gtest/gtest.h>

using namespace legwork;
using namespace legwork::render;
using legwork::render::testing::out_dir;

namespace {

// Left and right ankle heights of a real walk (07_02) over time.
LinePlot ankle_plot() {
  const Motion m = legwork::testdata::load_sample("cmu/bvh/walking/07_02.bvh");
  const int la = m.skeleton.find("LeftFoot"), ra = m.skeleton.find("RightFoot");
  std::vector<double> t, l, r;
  std::vector<Vec3> pos(static_cast<std::size_t>(m.joint_count()));
  for (int f = 0; f < m.frame_count(); ++f) {
    forward_positions(m.skeleton, m.frame(f), pos);
    t.push_back(f / m.fps);
    l.push_back(pos[static_cast<std::size_t>(la)].y());
    r.push_back(pos[static_cast<std::size_t>(ra)].y());
  }
  LinePlot p;
  p.title = "ankle heights, 07_02.bvh";
  p.x_label = "time (s)";
  p.panels.resize(2);
  p.panels[0].y_label = "left (m)";
  p.panels[0].series.push_back({"left ankle", t, l, kLeftColor});
  p.panels[0].ref_lines.push_back({0.1, "10 cm"});
  p.panels[1].y_label = "right (m)";
  p.panels[1].series.push_back({"right ankle", t, r, kRightColor});
  p.panels[1].bands.push_back({0.5, 1.0, kRightColor, "a marked second"});
  return p;
}

}  // namespace

TEST(Layout, RecordsEveryTextPanelAndLegendOfARealChart) {
  const std::string path = (out_dir() / "layout_ankles.png").string();
  LayoutRecorder rec;
  plot_lines(ankle_plot(), path);
  ASSERT_EQ(rec.pictures().size(), 1u);
  const PictureLayout& p = rec.pictures()[0];
  EXPECT_EQ(p.path, path);
  EXPECT_EQ(p.data_areas.size(), 2u);
  EXPECT_EQ(p.legends.size(), 2u);
  bool title = false, label = false, ref = false;
  for (const auto& t : p.texts) {
    title = title || t.text == "ankle heights, 07_02.bvh";
    label = label || t.text == "time (s)";
    ref = ref || t.text == "10 cm";
    EXPECT_GT(t.box.width(), 0) << t.text;
    EXPECT_GT(t.box.height(), 0) << t.text;
  }
  EXPECT_TRUE(title && label && ref);
  // The rotated y label is taller than wide.
  for (const auto& t : p.texts) {
    if (t.text == "left (m)") {
      EXPECT_GT(t.box.height(), t.box.width());
    }
  }
  // Legends sit outside the panels, in the right margin.
  for (const Box& l : p.legends) EXPECT_GE(l.x0, p.data_areas[0].x1);
  const auto problems = layout_problems(p);
  EXPECT_TRUE(problems.empty()) << problems.front();
}

TEST(Layout, BarChartValueLabelsDoNotOverlapEvenWhenCrowded) {
  BarChart c;
  c.title = "per-class error";
  c.groups = {"basketball", "boxing", "climbing", "running", "swimming", "walking", "dance", "golf"};
  c.series = {{"engine", {11.96, 13.41, 12.22, 8.71, 24.13, 8.12, 10.5, 9.9}},
              {"IK baseline", {11.04, 11.63, 8.31, 9.05, 12.11, 7.64, 10.1, 9.2}},
              {"document", {10.2, 11.1, 9.5, 8.8, 20.3, 7.9, 9.99, 8.88}}};
  c.width = 500;  // asked narrower than the labels need: the chart widens itself
  LayoutRecorder rec;
  plot_bars(c, (out_dir() / "layout_bars.svg").string());
  ASSERT_EQ(rec.pictures().size(), 1u);
  const PictureLayout& p = rec.pictures()[0];
  EXPECT_GT(p.width, 500);
  EXPECT_EQ(p.legends.size(), 1u);
  const auto problems = layout_problems(p);
  EXPECT_TRUE(problems.empty()) << problems.front();
}

TEST(Layout, ProblemsNameTheOverlappingTextsAndTheCoveredPanel) {
  PictureLayout p;
  p.path = "chart.png";
  p.width = 200;
  p.height = 100;
  p.texts = {{"12.3", {10, 10, 40, 20}}, {"12.9", {30, 12, 60, 22}}, {"apart", {100, 10, 130, 20}}, {"edge", {190, 50, 215, 60}}};
  p.data_areas = {{50, 30, 190, 90}};
  p.legends = {{150, 40, 198, 60}};
  const auto problems = layout_problems(p);
  ASSERT_EQ(problems.size(), 3u);
  EXPECT_EQ(problems[0], "chart.png: text '12.3' [10,10]-[40,20] overlaps '12.9' [30,12]-[60,22]");
  EXPECT_EQ(problems[1], "chart.png: text 'edge' [190,50]-[215,60] reaches outside the picture");
  EXPECT_EQ(problems[2], "chart.png: legend [150,40]-[198,60] covers the data area [50,30]-[190,90]");
  // Touching boxes (within the tolerance) are not a fault.
  p.texts = {{"a", {0, 0, 10, 10}}, {"b", {9.5, 0, 20, 10}}};
  p.legends.clear();
  EXPECT_TRUE(layout_problems(p).empty());
}

TEST(Layout, OneRecorderPerThreadAndNothingRecordedWithoutOne) {
  {
    LayoutRecorder rec;
    try {
      LayoutRecorder second;
      FAIL() << "a second recorder must be refused";
    } catch (const Error& e) {
      EXPECT_STREQ(e.what(), "a LayoutRecorder is already recording on this thread");
    }
  }
  plot_lines(ankle_plot(), (out_dir() / "layout_unrecorded.png").string());  // no recorder: no effect, no crash
  LayoutRecorder again;  // the first one's end freed the slot
  EXPECT_TRUE(again.pictures().empty());
}
