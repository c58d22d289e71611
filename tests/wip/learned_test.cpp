// The learned depth mapping's lookup (legwork/wip/learned.hpp) on the shipped
// table, which `legwork wip learn` built from the shared CMU walks, and the
// cycle coordinate on a real walk.
#include <legwork/wip/learned.hpp>
#include <legwork/wip/offline/learn.hpp>
#include <legwork/wip/offline/run.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <cmath>

namespace legwork::wip {
namespace {

const LearnedMapping& shipped() {
  static const LearnedMapping m = read_learned_mapping((testdata::source_dir() / "data/wip/learned_mapping.txt").string());
  return m;
}

constexpr int kN = LearnedMapping::kNodes;
double node(double i) { return 2.0 * i / (kN - 1); }

TEST(LearnedLookup, NodesAreExactBetweenNodesIsBilinearAndInputsAreClamped) {
  const auto& m = shipped();
  for (int l = 0; l < 2; ++l)
    for (int i : {0, 7, kN - 1})
      for (int j : {0, 5, kN - 1}) EXPECT_DOUBLE_EQ(m.lookup(node(i), node(j), l), m.at(l, i, j));
  EXPECT_NEAR(m.lookup(node(3.5), node(4), 1), 0.5 * (m.at(1, 3, 4) + m.at(1, 4, 4)), 1e-12);
  EXPECT_NEAR(m.lookup(node(6), node(2.25), 0), 0.75 * m.at(0, 6, 2) + 0.25 * m.at(0, 6, 3), 1e-12);
  EXPECT_DOUBLE_EQ(m.lookup(-1, 3, 0), m.at(0, 0, kN - 1));
  EXPECT_DOUBLE_EQ(m.lookup(NAN, 0, 1), m.at(1, 0, 0));
  EXPECT_DOUBLE_EQ(m.lookup(0.5, 0.7, -1), 0.5 * (m.lookup(0.5, 0.7, 0) + m.lookup(0.5, 0.7, 1)));
}

TEST(LearnedLookup, TheTableLearnedFromRealWalksPutsTheLeadingFootInFrontAndSwingsForward) {
  const auto& m = shipped();
  EXPECT_GT(m.samples, 5000);
  // Both feet down: the foot that landed last is in front of the pelvis, the other behind.
  EXPECT_GT(m.lookup(0, 0, 1), 0);
  EXPECT_LT(m.lookup(0, 0, 0), 0);
  // A swinging foot (the other one down, it landed last) moves from behind to in front.
  EXPECT_LT(m.lookup(0.3, 0, 0), 0);
  EXPECT_GT(m.lookup(1.9, 0, 0), 0);
  EXPECT_GT(m.lookup(1.9, 0, 0), m.lookup(1.2, 0, 0));
  // The supporting foot moves back while the other one swings.
  EXPECT_GT(m.lookup(0, 0.3, 1), m.lookup(0, 1.9, 1));
}

TEST(LearnedLookup, TheGainFollowsTheApexWithinItsRange) {
  LearnedMapping m = shipped();
  EXPECT_DOUBLE_EQ(m.gain(m.apex_mean), 1.0);
  m.gain_slope = 4;
  EXPECT_NEAR(m.gain(m.apex_mean + 0.05), 1.2, 1e-12);
  EXPECT_DOUBLE_EQ(m.gain(m.apex_mean + 10), m.gain_max);
  EXPECT_DOUBLE_EQ(m.gain(m.apex_mean - 10), m.gain_min);
  EXPECT_DOUBLE_EQ(m.gain(NAN), 1.0);
}

TEST(CycleCoordinate, RisesThroughTheSwingAndRestsAtZeroOnARealWalk) {
  const Motion walk = testdata::load_sample("cmu/bvh/walking/05_01.bvh");
  const Model model = make_model(walk.skeleton);
  RunOptions ro;
  ro.calibrate = false;
  ro.keep_poses = false;
  const auto frames = run_wip(model, tracker_frames_from_motion(walk, 30), ro).frames;
  int descending = 0, rising = 0;
  for (const auto& fr : frames)
    for (int f = 0; f < 2; ++f) {
      EXPECT_GE(fr.cycle[f], 0);
      EXPECT_LE(fr.cycle[f], 2);
      const bool down = fr.phase[f] == GaitPhase::MidSwing || fr.phase[f] == GaitPhase::TerminalSwing;
      if (down) {
        EXPECT_GE(fr.cycle[f], 1);
        ++descending;
      } else {
        EXPECT_LE(fr.cycle[f], 1);
        ++rising;
      }
    }
  EXPECT_GT(descending, 20);
  EXPECT_GT(rising, 20);
  // The lead foot is the one that struck last.
  int lead = -1;
  for (const auto& fr : frames) {
    for (int f = 0; f < 2; ++f)
      if (fr.events[f] & kEventFootStrike) lead = f;
    EXPECT_EQ(fr.lead, lead) << fr.time;
  }
  EXPECT_GE(lead, 0);
}

}  // namespace
}  // namespace legwork::wip
