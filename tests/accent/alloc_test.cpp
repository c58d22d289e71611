// Accentuator::update() allocates nothing: global operator new is counted
// while a warmed-up avatar runs over a real trial in every search mode.
#include <legwork/accent/accentuator.hpp>
#include <legwork/core/interpolate.hpp>

#include "accent_testing.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<long> g_allocations{0};
std::atomic<bool> g_counting{false};
}  // namespace

void* operator new(std::size_t n) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace legwork::accent {
namespace {

TEST(AccentAlloc, UpdateIsAllocationFree) {
  Database db = build_database(testing::sample_trials({"walking/07_01", "walking/05_01", "running/09_01"}), BuildConfig{});
  db.build_index();
  const auto frames = tracker_frames_from_motion(resample(testing::sample_trial("walking/07_02").motion, 90.0));
  for (SearchMode mode : {SearchMode::BruteForce, SearchMode::Exact, SearchMode::Fast}) {
    AccentConfig cfg;
    cfg.search = mode;
    Accentuator acc(db, cfg);
    for (std::size_t f = 0; f < 10; ++f) acc.update(frames[f]);
    g_allocations = 0;
    g_counting = true;
    for (std::size_t f = 10; f < frames.size(); ++f) {
      TrackerFrame t = frames[f];
      if (f % 50 == 0) t.left.valid = false;  // the fallback path too
      acc.update(t);
    }
    g_counting = false;
    EXPECT_EQ(g_allocations.load(), 0) << "mode " << static_cast<int>(mode);
  }
}

}  // namespace
}  // namespace legwork::accent
