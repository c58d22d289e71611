// Synthetic in-place stepping and tracker corruption.
#include <legwork/wip/offline/synthetic.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace legwork::wip {
namespace {

TEST(Synthetic, IsDeterministicPerSeedAndLiftsOnlyDuringTrueSwings) {
  SyntheticOptions o;
  o.noise = 0;
  o.drop_rate = o.nan_rate = 0;
  const auto a = synthetic_stepping(o), b = synthetic_stepping(o);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  EXPECT_EQ(a.frames.size(), static_cast<std::size_t>(std::floor(o.duration * o.rate)) + 1);
  ASSERT_FALSE(a.swings.empty());
  for (const auto& s : a.swings) EXPECT_FALSE(s.off < o.pause_start + o.pause_length && s.strike > o.pause_start);
  for (std::size_t i = 0; i < a.frames.size(); ++i)
    for (int f = 0; f < 2; ++f) {
      EXPECT_EQ(a.frames[i].foot(f).position, b.frames[i].foot(f).position);
      bool swinging = false;
      for (const auto& s : a.swings) swinging |= s.foot == f && a.frames[i].time > s.off && a.frames[i].time < s.strike;
      const double lift = a.frames[i].foot(f).position.y() - o.ankle_height;
      if (!swinging) {
        EXPECT_NEAR(lift, 0.0, 1e-12) << a.frames[i].time;
      }
    }
  EXPECT_FALSE(a.frames[0].head().valid);
}

TEST(Synthetic, RefusesOverlongOutputsNamingTheLimit) {
  SyntheticOptions o;
  o.duration = 1e6;
  try {
    synthetic_stepping(o);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("limit of 10000000 frames"), std::string::npos) << e.what();
  }
}

TEST(Synthetic, NoiseJittersAndDropsTheFeet) {
  SyntheticOptions o;
  o.noise = 0;
  o.drop_rate = o.nan_rate = 0;
  auto frames = synthetic_stepping(o).frames;
  const auto clean = frames;
  add_tracker_noise(frames, 0.01, 0.1, 7);
  int dropped = 0;
  double sum2 = 0;
  for (std::size_t i = 0; i < frames.size(); ++i)
    for (int f = 0; f < 2; ++f) {
      dropped += frames[i].foot(f).valid ? 0 : 1;
      sum2 += (frames[i].foot(f).position - clean[i].foot(f).position).squaredNorm();
    }
  const double n = 2.0 * static_cast<double>(frames.size());
  EXPECT_NEAR(dropped / n, 0.1, 0.02);
  EXPECT_NEAR(std::sqrt(sum2 / (3 * n)), 0.01, 0.001);
}

}  // namespace
}  // namespace legwork::wip
