// The learned depth mapping's lookup (legwork/wip/learned.hpp) on the shipped
// table, which `legwork wip learn` built from the shared CMU walks, and the
// cycle coordinate on a real walk.
#include <legwork/wip/learned.hpp>
#include <legwork/wip/offline/learn.hpp>
#include <legwork/wip/offline/run.hpp>

#include "sample_walk_run.hpp"
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

constexpr int kS = LearnedMapping::kSinceNodes;
double since(int k) { return LearnedMapping::kSince[static_cast<std::size_t>(k)]; }

TEST(LearnedLookup, NodesAreExactBetweenNodesIsMultilinearAndInputsAreClamped) {
  const auto& m = shipped();
  for (int l = 0; l < 2; ++l)
    for (int k : {0, 2, kS - 1})
      for (int i : {0, 7, kN - 1})
        for (int j : {0, 5, kN - 1}) EXPECT_DOUBLE_EQ(m.lookup(node(i), node(j), l, since(k)), m.at(l, k, i, j));
  EXPECT_NEAR(m.lookup(node(3.5), node(4), 1, since(1)), 0.5 * (m.at(1, 1, 3, 4) + m.at(1, 1, 4, 4)), 1e-12);
  EXPECT_NEAR(m.lookup(node(6), node(2.25), 0, since(2)), 0.75 * m.at(0, 2, 6, 2) + 0.25 * m.at(0, 2, 6, 3), 1e-12);
  EXPECT_NEAR(m.lookup(node(6), node(2), 0, 0.5 * (since(1) + since(2))), 0.5 * (m.at(0, 1, 6, 2) + m.at(0, 2, 6, 2)),
              1e-12);
  EXPECT_DOUBLE_EQ(m.lookup(-1, 3, 0, -5), m.at(0, 0, 0, kN - 1));
  EXPECT_DOUBLE_EQ(m.lookup(NAN, 0, 1, 1e9), m.at(1, kS - 1, 0, 0));
  EXPECT_DOUBLE_EQ(m.lookup(NAN, 0, 1, NAN), m.at(1, kS - 1, 0, 0));
  EXPECT_DOUBLE_EQ(m.lookup(0.5, 0.7, -1, 0.2), 0.5 * (m.lookup(0.5, 0.7, 0, 0.2) + m.lookup(0.5, 0.7, 1, 0.2)));
}

TEST(LearnedLookup, TheTableLearnedFromRealWalksPutsTheLeadingFootInFrontAndSwingsForward) {
  const auto& m = shipped();
  EXPECT_GT(m.samples, 5000);
  // Both feet down just after a landing: the foot that landed is in front of the pelvis, the other behind.
  EXPECT_GT(m.lookup(0, 0, 1, 0.05), 0);
  EXPECT_LT(m.lookup(0, 0, 0, 0.05), 0);
  // A swinging foot (the other one down, it landed last) moves from behind to in front.
  EXPECT_LT(m.lookup(0.3, 0, 0, 0.3), 0);
  EXPECT_GT(m.lookup(1.9, 0, 0, 0.5), 0);
  EXPECT_GT(m.lookup(1.9, 0, 0, 0.5), m.lookup(1.2, 0, 0, 0.4));
  // The supporting foot moves back while the other one swings.
  EXPECT_GT(m.lookup(0, 0.3, 1, 0.3), m.lookup(0, 1.9, 1, 0.5));
}

TEST(LearnedLookup, TheAmplitudeFollowsApexAndCadenceWithinItsRange) {
  LearnedMapping m = shipped();
  EXPECT_GT(m.amplitude_min, 0);
  EXPECT_LE(m.amplitude_min, m.amplitude_max);
  m.amplitude_intercept = 0.3;
  m.amplitude_slope = 1;
  m.cadence_slope = 0.1;
  m.amplitude_min = 0.2;
  m.amplitude_max = 0.6;
  EXPECT_NEAR(m.amplitude(0.1, 1.0), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(m.amplitude(10, 1), 0.6);
  EXPECT_DOUBLE_EQ(m.amplitude(-10, 1), 0.2);
  EXPECT_NEAR(m.amplitude(NAN, NAN), 0.3 + m.apex_mean + 0.1 * m.cadence_mean, 1e-12);
  EXPECT_NEAR(m.depth(0.4, 1.1, 1, 0.3, 0.1, 1.0, 0.0), 0.5 * m.lookup(0.4, 1.1, 1, 0.3) * m.turn_gain(0), 1e-12);
}

TEST(LearnedLookup, StepsLearnedFromRealWalksShortenInTurnsAndTheGainIsClamped) {
  const auto& m = shipped();
  // The shared walks' turn-arounds: the faster the head turns, the shorter the steps.
  EXPECT_LT(m.turn_slope, 0);
  EXPECT_GT(m.turn_gain(0), m.turn_gain(1.0));
  EXPECT_GE(m.turn_gain(1e9), 0);
  LearnedMapping t = m;
  t.turn_intercept = 1.2;
  t.turn_slope = -0.5;
  EXPECT_NEAR(t.turn_gain(1.0), 0.7, 1e-12);
  EXPECT_NEAR(t.turn_gain(-1.0), 0.7, 1e-12);  // a rate's sign is the turn's side, not its speed
  EXPECT_DOUBLE_EQ(t.turn_gain(NAN), 1.2);      // unknown: no turn
  t.turn_slope = -0.2;
  EXPECT_DOUBLE_EQ(t.turn_gain(100), 1.2 - 0.2 * LearnedMapping::kMaxTurnRate);  // the rate is clamped
  t.turn_slope = -5;
  EXPECT_DOUBLE_EQ(t.turn_gain(3), 0);  // the gain never flips the depth
  t.turn_slope = 5;
  EXPECT_DOUBLE_EQ(t.turn_gain(3), LearnedMapping::kMaxTurnGain);
}

TEST(LearnedFormat, FormatOneTablesStillReadWithoutATurnTerm) {
  std::string text = format_learned_mapping(shipped(), "test");
  ASSERT_EQ(text.rfind("legwork-wip-learned-mapping 2\n", 0), 0u);
  const LearnedMapping back = parse_learned_mapping(text, "v2.txt");
  EXPECT_DOUBLE_EQ(back.turn_intercept, shipped().turn_intercept);
  EXPECT_DOUBLE_EQ(back.turn_slope, shipped().turn_slope);
  // The same table as format 1: the header and no turn lines.
  text.replace(0, std::string("legwork-wip-learned-mapping 2").size(), "legwork-wip-learned-mapping 1");
  const auto a = text.find("turn_intercept "), b = text.find("samples ");
  ASSERT_LT(a, b);
  text.erase(a, b - a);
  const LearnedMapping v1 = parse_learned_mapping(text, "v1.txt");
  EXPECT_EQ(v1.turn_intercept, 1.0);
  EXPECT_EQ(v1.turn_slope, 0.0);
  EXPECT_EQ(v1.shape, back.shape);
  // A format 2 table without its turn lines names the missing key and the line.
  std::string cut = format_learned_mapping(shipped(), "test");
  const auto c = cut.find("turn_intercept "), d = cut.find("samples ");
  cut.erase(c, d - c);
  try {
    parse_learned_mapping(cut, "cut.txt");
    FAIL() << "a format 2 table without turn lines was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cut.txt:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("expected 'turn_intercept <number>'"), std::string::npos) << e.what();
  }
}

TEST(CycleCoordinate, RisesThroughTheSwingAndRestsAtZeroOnARealWalk) {
  const auto& frames = samples::sample_walk_run().frames;
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
