// The one foot-contact detector (walking-in-place ground truth, walk-cycle
// extraction, the key-frame baseline's cycle, footprints), on real CMU walks
// and runs from the repo's sample.
#include <legwork/core/contacts.hpp>

#include "cmu_sample.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace legwork;

namespace {

int strikes_between(const std::vector<int>& s, int a, int b) {
  return static_cast<int>(std::count_if(s.begin(), s.end(), [&](int f) { return f >= a && f < b; }));
}

}  // namespace

TEST(Contacts, AWalkAlternatesFeetWithDoubleSupportAndNoFlight) {
  const Motion m = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  const auto down = foot_contacts(m);
  ASSERT_EQ(down[0].size(), static_cast<std::size_t>(m.frame_count()));
  int flight = 0, both = 0;
  for (int f = 0; f < m.frame_count(); ++f) {
    flight += !down[0][static_cast<std::size_t>(f)] && !down[1][static_cast<std::size_t>(f)];
    both += down[0][static_cast<std::size_t>(f)] && down[1][static_cast<std::size_t>(f)];
  }
  EXPECT_LT(flight, m.frame_count() / 20) << "a walk has (almost) no frames with both feet in the air";
  EXPECT_GT(both, m.frame_count() / 10) << "a walk has double support";
  const auto swings = foot_swings(m);
  ASSERT_GE(swings.size(), 4u);
  for (std::size_t i = 1; i < swings.size(); ++i) {
    EXPECT_NE(swings[i].foot, swings[i - 1].foot) << "swings alternate feet, at " << swings[i].off << " s";
    EXPECT_GT(swings[i].off, swings[i - 1].off);
  }
  for (const auto& s : swings) {
    EXPECT_GT(s.strike - s.off, 0.25) << "a walking swing lasts ~0.4 s";
    EXPECT_LT(s.strike - s.off, 0.7);
    EXPECT_GT(s.apex, 0.03);
  }
}

TEST(Contacts, StrikesMatchSwingsAndIncludeOneUnderWayAtTheStart) {
  const Motion run = testdata::load_sample("cmu/bvh/running/09_01.bvh");
  const auto down = foot_contacts(run);
  int flight = 0;
  for (int f = 0; f < run.frame_count(); ++f) flight += !down[0][static_cast<std::size_t>(f)] && !down[1][static_cast<std::size_t>(f)];
  EXPECT_GT(flight, run.frame_count() / 10) << "a run has flight phases";
  for (int foot = 0; foot < 2; ++foot) {
    const auto strikes = foot_strikes(run, foot);
    for (const auto& s : foot_swings(run)) {
      if (s.foot != foot) continue;
      const int f = static_cast<int>(std::lround(s.strike * run.fps));
      EXPECT_EQ(strikes_between(strikes, f, f + 1), 1) << "every complete swing ends in a strike";
    }
    for (int f : strikes) {
      EXPECT_TRUE(down[static_cast<std::size_t>(foot)][static_cast<std::size_t>(f)]);
      EXPECT_FALSE(down[static_cast<std::size_t>(foot)][static_cast<std::size_t>(f - 1)]);
    }
  }
  // The right foot is in the air at the clip's first frame: its strike counts.
  const auto right = foot_strikes(run, 1);
  ASSERT_FALSE(down[1][0]);
  ASSERT_FALSE(right.empty());
  EXPECT_LT(right.front(), static_cast<int>(0.5 * run.fps));
}

TEST(Contacts, NeedsAnklesAndSaysSo) {
  Motion m = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  m.skeleton.roles[Role::LeftAnkle] = -1;
  try {
    (void)foot_contacts(m);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "foot contacts need ankle joints (roles left_ankle/right_ankle)");
  }
}

// 07_01 ends while a foot is in the air: by default that swing is left out
// (no strike); with end_swings it is kept, flagged cut, its strike at the
// clip's end, its foot-off where the foot really left the floor (after the
// other foot's last complete swing began), and the complete swings are unchanged.
TEST(Contacts, ASwingTheClipsEndCutsIsKeptOnRequestWithItsFootOff) {
  const Motion m = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  const auto complete = foot_swings(m);
  ContactOptions opt;
  opt.end_swings = true;
  const auto all = foot_swings(m, opt);
  ASSERT_EQ(all.size(), complete.size() + 1) << "07_01 ends mid-swing";
  int cut = 0;
  for (const auto& s : all) {
    if (!s.cut) continue;
    ++cut;
    EXPECT_NEAR(s.strike, m.frame_count() / m.fps, 1e-9);
    EXPECT_GE(s.strike - s.off, 0.05);
    EXPECT_GT(s.off, complete.back().off) << "the cut swing is the last one";
    EXPECT_GT(s.apex, 0.03) << "a real lift, not a heel rise";
  }
  EXPECT_EQ(cut, 1);
  for (const auto& s : complete) EXPECT_FALSE(s.cut);
}
