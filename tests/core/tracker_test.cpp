// The shared per-frame input and time rules (core/tracker.hpp).
#include <legwork/core/tracker.hpp>

#include <gtest/gtest.h>

#include <limits>

namespace legwork {
namespace {

using V = FrameClock::Verdict;

TEST(FrameClock, AcceptsIncreasingTimeWithDt) {
  FrameClock c;
  EXPECT_EQ(c.advance(10.0).verdict, V::Accept);
  const auto s = c.advance(10.25);
  EXPECT_EQ(s.verdict, V::Accept);
  EXPECT_DOUBLE_EQ(s.dt, 0.25);
}

TEST(FrameClock, RejectsNonFiniteAndAbsurdTimesWithoutStarting) {
  FrameClock c;
  EXPECT_EQ(c.advance(std::numeric_limits<double>::quiet_NaN()).verdict, V::Reject);
  EXPECT_EQ(c.advance(std::numeric_limits<double>::infinity()).verdict, V::Reject);
  EXPECT_EQ(c.advance(1e30).verdict, V::Reject);
  EXPECT_FALSE(c.started());
  // A NaN first sample must not freeze the stream: the next good one starts it.
  EXPECT_EQ(c.advance(0.5).verdict, V::Accept);
  EXPECT_EQ(c.advance(0.6).verdict, V::Accept);
}

TEST(FrameClock, RejectsDuplicateAndBackwardTime) {
  FrameClock c;
  c.advance(1.0);
  EXPECT_EQ(c.advance(1.0).verdict, V::Reject);
  EXPECT_EQ(c.advance(0.9).verdict, V::Reject);
  EXPECT_DOUBLE_EQ(c.last_time(), 1.0);
  EXPECT_EQ(c.advance(1.1).verdict, V::Accept);
}

TEST(FrameClock, RecoversFromAFarFutureSpike) {
  FrameClock c;
  c.advance(0.0);
  EXPECT_EQ(c.advance(1e8).verdict, V::Restart);  // a gap over kMaxGap restarts
  // Good frames now look backward; after kRestartFrames increasing ones the clock restarts on them.
  int rejected = 0;
  V last = V::Reject;
  for (int i = 1; i <= 20 && last != V::Restart; ++i) {
    last = c.advance(i / 90.0).verdict;
    rejected += last == V::Reject;
  }
  EXPECT_EQ(last, V::Restart);
  EXPECT_EQ(rejected, FrameClock::kRestartFrames - 1);
  EXPECT_EQ(c.advance(21 / 90.0).verdict, V::Accept);
}

TEST(FrameClock, RandomBackwardJitterDoesNotRestart) {
  FrameClock c;
  c.advance(5.0);
  // Alternating old timestamps (not an increasing run) never restart.
  for (int i = 0; i < 50; ++i) EXPECT_EQ(c.advance(i % 2 ? 4.0 : 3.0).verdict, V::Reject);
}

TEST(Tracker, UsableRejectsInvalidNonFiniteAndHugeSamples) {
  DevicePose d{Vec3(0.1, 1.6, 0), Quat::Identity(), true};
  EXPECT_TRUE(usable(d));
  d.valid = false;
  EXPECT_FALSE(usable(d));
  d = {Vec3(1e30, 0, 0), Quat::Identity(), true};
  EXPECT_FALSE(usable(d));
  d = {Vec3(0, std::numeric_limits<double>::quiet_NaN(), 0), Quat::Identity(), true};
  EXPECT_FALSE(usable(d));
  d = {Vec3::Zero(), Quat(0, 0, 0, 0), true};
  EXPECT_FALSE(usable(d));
}

}  // namespace
}  // namespace legwork
