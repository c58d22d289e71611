// accent::update() allocates nothing: global operator new is counted
// while a warmed-up avatar runs over a real trial in every search mode.
#include <legwork/accent/accent.hpp>
#include <legwork/core/interpolate.hpp>

#include "accent_testing.hpp"

#include <gtest/gtest.h>

#include "alloc_counter.hpp"

namespace legwork::accent {
namespace {

TEST(AccentAlloc, UpdateIsAllocationFree) {
  const Database db = testing::indexed_database({"walking/07_01", "walking/05_01", "running/09_01"});
  const auto frames = tracker_frames_from_motion(testing::tracker_rate_trial("walking/07_02"));
  for (SearchMode mode : {SearchMode::BruteForce, SearchMode::Exact, SearchMode::Fast}) {
    Settings cfg;
    cfg.search = mode;
    testing::Avatar acc(db, cfg);
    for (std::size_t f = 0; f < 10; ++f) acc.update(frames[f]);
    std::vector<TrackerFrame> live(frames.begin() + 10, frames.end());
    for (std::size_t f = 0; f < live.size(); f += 50) live[f].hand(kLeft).valid = false;  // the fallback path too
    long locked = 0;  // foot locking runs in the counted frames
    const long allocations = legwork::alloc_count::count_allocations([&] {
      for (const TrackerFrame& t : live) {
        const Info info = acc.update(t);
        locked += info.foot_locked[0] + info.foot_locked[1];
      }
    });
    EXPECT_EQ(allocations, 0) << "mode " << static_cast<int>(mode);
    EXPECT_GT(locked, static_cast<long>(live.size()) / 4) << "mode " << static_cast<int>(mode);
  }
}

}  // namespace
}  // namespace legwork::accent
