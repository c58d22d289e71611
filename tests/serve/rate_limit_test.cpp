// The per-session rate limit (rate_limit.hpp) on the head timestamps of a real
// CMU walk, with the server clock driven by the test.
#include <legwork/serve/rate_limit.hpp>

#include <legwork/core/tracker.hpp>
#include <legwork/io/bvh.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace legwork::serve {
namespace {

using Clock = RateLimiter::Clock;

// 07_02's frame times sampled at `hz` (T-pose dropped), as a client would stamp them.
std::vector<double> trial_times(double hz) {
  io::BvhReadOptions o;
  o.drop_first_frame = true;
  const Motion m = io::load_bvh(std::string(LEGWORK_SOURCE_DIR) + "/data/cmu/bvh/walking/07_02.bvh", o);
  std::vector<double> t;
  for (const TrackerFrame& f : tracker_frames_from_motion(m, hz)) t.push_back(f.time);
  return t;
}

Clock::time_point at(Clock::time_point t0, double seconds) {
  return t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

struct Tally {
  int accepted = 0, too_fast = 0, clock = 0;
  void add(RateVerdict v) {
    accepted += v == RateVerdict::Accept;
    too_fast += v == RateVerdict::TooFastForItsTime;
    clock += v == RateVerdict::TooFastForTheClock;
  }
};

TEST(RateLimit, HonestFramesBunchedByAStalledServerAreAllAccepted) {
  const auto t = trial_times(90);
  ASSERT_GE(t.size(), 240U);  // 2.7 s
  const Clock::time_point t0{};
  RateLimiter r(120, t0);
  Tally n;
  // Half a second in step, then the server stalls for 1.5 s: the 135 frames
  // sent meanwhile wait in the socket and are read at the same instant; then in step again.
  const double stall_end = t[45] + 1.5;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double arrival = (i >= 45 && t[i] < stall_end) ? stall_end : t[i];
    n.add(r.admit(t[i], at(t0, arrival)));
  }
  EXPECT_EQ(n.accepted, static_cast<int>(t.size()));
}

TEST(RateLimit, RepeatedStallsAtExactlyTheMaximumRateLoseNothing) {
  const auto t = trial_times(120);
  ASSERT_GE(t.size(), 320U);  // 2.7 s: five stalls
  const Clock::time_point t0{};
  RateLimiter r(120, t0);
  Tally n;
  // Every frame waits for the next half-second boundary (the server thread is
  // stalled for half a second, over and over).
  for (const double ti : t) n.add(r.admit(ti, at(t0, std::ceil(ti * 2 + 1e-9) / 2)));
  EXPECT_EQ(n.accepted, static_cast<int>(t.size()));
}

TEST(RateLimit, AClientSendingFasterThanTheLimitInItsOwnTimeIsDropped) {
  const auto t = trial_times(240);  // 240 Hz of the client's time, sent in real time
  ASSERT_GE(t.size(), 480U);
  const Clock::time_point t0{};
  RateLimiter r(120, t0);
  Tally n;
  for (std::size_t i = 0; i < 480; ++i) n.add(r.admit(t[i], at(t0, t[i] - t[0])));
  // The quarter-second burst, then 120 Hz over the frames' 2 s span.
  const double span = t[479] - t[0];
  const double expected = 120 * RateLimiter::kStreamBurstSeconds + 120 * span;
  EXPECT_NEAR(n.accepted, expected, 1.0);
  EXPECT_EQ(n.too_fast, 480 - n.accepted);
  EXPECT_EQ(n.clock, 0);
}

TEST(RateLimit, AClientSendingTooFastAsABurstIsDroppedTheSame) {
  const auto t = trial_times(240);  // the same frames, all at once
  const Clock::time_point t0{};
  RateLimiter r(120, t0);
  Tally n;
  for (std::size_t i = 0; i < 200; ++i) n.add(r.admit(t[i], t0));
  EXPECT_NEAR(n.accepted, 120 * RateLimiter::kStreamBurstSeconds + 120 * (t[199] - t[0]), 1.0);
  EXPECT_GT(n.too_fast, 0);
}

TEST(RateLimit, FakeTimestampsAreBoundedByTheWallClock) {
  const Clock::time_point t0{};
  RateLimiter r(120, t0);
  Tally n;
  // A second of wall time at 1000 frames/s, each frame claiming to be a second
  // after the last (or, every other frame, back again): the stream bucket is
  // always full, the wall-clock ceiling is what holds.
  for (int i = 0; i < 1000; ++i) n.add(r.admit(i % 4 == 3 ? 0.0 : i, at(t0, i / 1000.0)));
  const double ceiling = r.ceiling_hz() * 1.0 + 120 * RateLimiter::kCeilingBurstSeconds;
  EXPECT_LE(n.accepted, ceiling + 1);
  EXPECT_GE(n.accepted, ceiling - 2);
  EXPECT_EQ(n.clock, 1000 - n.accepted);
  // and it stays bounded: the next ten seconds at 1000 frames/s get 240 Hz
  Tally later;
  for (int i = 0; i < 10000; ++i) later.add(r.admit(1000.0 + i, at(t0, 1.0 + i / 1000.0)));
  EXPECT_NEAR(later.accepted, r.ceiling_hz() * 10, 2);
}

TEST(RateLimit, FramesStampedWithOneInstantGetOnlyTheBurst) {
  const Clock::time_point t0{};
  RateLimiter r(120, t0);
  Tally n;
  // 100 frames stamped t = 5 s arrive over 10 s of wall time: no time of their own passes.
  for (int i = 0; i < 100; ++i) n.add(r.admit(5.0, at(t0, i * 0.1)));
  EXPECT_EQ(n.accepted, static_cast<int>(120 * RateLimiter::kStreamBurstSeconds));
  EXPECT_EQ(n.too_fast, 100 - n.accepted);
}

}  // namespace
}  // namespace legwork::serve
