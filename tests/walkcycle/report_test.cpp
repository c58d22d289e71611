// Walk-cycle reports (offline/report.cpp): the report's figures are the
// measures' own, the arc CSV has one row per frame with the keys named, and
// an unknown joint is refused by name.
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/report.hpp>

#include "testdata.hpp"
#include "walk_samples.hpp"

#include <algorithm>

using namespace legwork;
using namespace legwork::walkcycle;
using namespace legwork::walkcycle::samples;

TEST(WalkReport, CycleFieldsAreTheMeasures) {
  const auto& s = cmu_skeleton();
  const CycleModel m = build_cycle(s, read_walk_keys(walk_file("normal"), s));
  std::string text;
  const auto r = cycle_report(m, "normal", text);
  EXPECT_EQ(r["walk"], "normal");
  EXPECT_EQ(r["frames_per_cycle"], m.frames_per_cycle);
  EXPECT_DOUBLE_EQ(r["step_length_m"].get<double>(), round6(step_length(m)));
  EXPECT_DOUBLE_EQ(r["loop_seam_error_m"].get<double>(), measure_loop_seam(m).position_m);
  EXPECT_EQ(r["key_foot_height_mm"].size(), 5u);
  EXPECT_EQ(text.rfind("cycle: " + std::to_string(m.frames_per_cycle) + " frames", 0), 0u) << text;
}

TEST(WalkReport, ArcCsvHasOneRowPerFrameWithTheKeys) {
  const auto& s = cmu_skeleton();
  const CycleModel m = build_cycle(s, read_walk_keys(walk_file("normal"), s));
  const ArcFigures a = arc_figures(m, "LeftHand");
  EXPECT_EQ(a.name, "LeftHand");
  const std::string csv = arc_csv(a);
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), a.arc.points.size() + 1);
  EXPECT_NE(csv.find(",contact\n"), std::string::npos);
  EXPECT_NE(csv.find(",up2\n"), std::string::npos);
  const auto j = arc_report(a, "x.csv");
  EXPECT_EQ(j["jerky"].get<bool>(), a.smooth.jerk_ratio > 5.0 && a.smooth.extent_m > 0.1);
  EXPECT_NE(arc_summary(a).find("arc LeftHand: spans"), std::string::npos);
}

TEST(WalkReport, UnknownArcJointIsNamed) {
  const auto& s = cmu_skeleton();
  const CycleModel m = build_cycle(s, read_walk_keys(walk_file("normal"), s));
  try {
    arc_figures(m, "Tail");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "--arc: unknown joint 'Tail'");
  }
}
