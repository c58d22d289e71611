// Key poses from mocap: events per step, steadiness, re-synthesis error,
// on the repo's sample walks (always) and on every shared CMU walking trial.
#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/extract.hpp>
#include <legwork/walkcycle/offline/measure.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <cstdio>
#include <filesystem>

using namespace legwork;
using namespace legwork::walkcycle;

namespace {


// Checks one trial; returns its resynthesis mean (mm) or -1 if it has too
// few steady steps (turn / stop trials).
double check_trial(const std::filesystem::path& file, double bound_mm) {
  io::BvhReadOptions o;
  o.drop_first_frame = true;
  const Motion clip = io::load_bvh(file.string(), o);
  Extraction ex;
  try {
    ex = extract_walk(clip);
  } catch (const Error& e) {
    std::printf("[walkcycle] %-12s no steady walk: %s\n", file.filename().string().c_str(), e.what());
    return -1;
  }
  // Monotonic events within each step, steps in time order, feet alternating.
  int prev_next = -1;
  for (const auto& s : ex.steps) {
    EXPECT_LT(s.contact, s.down) << file;
    EXPECT_LT(s.down, s.pass) << file;
    EXPECT_LT(s.pass, s.up) << file;
    EXPECT_LT(s.up, s.next_contact) << file;
    EXPECT_GE(s.contact, prev_next) << file;
    prev_next = s.next_contact;
  }
  // Periodic: the steady steps' durations agree (coefficient of variation).
  double sum = 0, sum2 = 0;
  int n = 0;
  for (const auto& s : ex.steps)
    if (s.used) {
      const double d = s.next_contact - s.contact;
      sum += d, sum2 += d * d, ++n;
    }
  const double mean = sum / n, cv = std::sqrt(std::max(0.0, sum2 / n - mean * mean)) / mean;
  EXPECT_LT(cv, 0.15) << file;
  EXPECT_GT(ex.cycle_seconds, 0.6) << file;
  EXPECT_LT(ex.cycle_seconds, 2.6) << file;
  // Re-synthesised cycle vs the clip's mean cycle.
  std::printf("[walkcycle] %-12s %2zu steps (%2d steady), cycle %.2f s, timing %.1f/%.1f/%.1f of %d, resynthesis %.1f mm mean, %.1f mm max\n",
              file.filename().string().c_str(), ex.steps.size(), ex.steps_used, ex.cycle_seconds, ex.keys.key_frames[1],
              ex.keys.key_frames[2], ex.keys.key_frames[3], ex.keys.frames_per_cycle, ex.resynthesis_mean_mm, ex.resynthesis_max_mm);
  EXPECT_LT(ex.resynthesis_mean_mm, bound_mm) << file;
  // The extracted file reads back and builds a cycle whose feet touch the floor at the keys.
  const std::string text = format_walk_keys(ex.keys, clip.skeleton);
  const WalkKeys again = parse_walk_keys(text, clip.skeleton, file.string());
  const CycleModel m = build_cycle(clip.skeleton, again);
  if (file.filename() != "09_12.bvh") {  // (09_12 steps sideways and back)
    EXPECT_GT(step_length(m), 0.2) << file;
  }
  EXPECT_LT(measure_loop_seam(m).velocity_mps, 1e-4) << file;
  return ex.resynthesis_mean_mm;
}

}  // namespace

TEST(Extract, SampleWalks) {
  int ok = 0;
  for (const auto& e : std::filesystem::directory_iterator(testdata::sample("cmu/bvh/walking"))) {
    if (check_trial(e.path(), 25.0) >= 0) ++ok;
  }
  EXPECT_EQ(ok, 7);
}

TEST(Extract, SameClipSameFile) {
  const Motion clip = testdata::load_sample("cmu/bvh/walking/16_15.bvh");
  EXPECT_EQ(format_walk_keys(extract_walk(clip).keys, clip.skeleton), format_walk_keys(extract_walk(clip).keys, clip.skeleton));
}

TEST(Extract, KeysFromFramesPutTheLeftFootForward) {
  const Motion clip = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  const auto ex = extract_walk(clip);
  const StepEvents& s = ex.steps.front();
  const WalkKeys k = keys_from_frames(clip, {s.contact, s.down, s.pass, s.up}, 24, 24);
  const CycleModel m = build_cycle(clip.skeleton, k);
  const auto p = joint_positions(clip.skeleton, m.step_keys[0]);
  EXPECT_GT(p[static_cast<std::size_t>(m.left.ankle)].z(), p[static_cast<std::size_t>(m.right.ankle)].z());
  EXPECT_GT(step_length(m), 0.3);
  EXPECT_THROW(keys_from_frames(clip, {5, 3, 6, 9}, 24, 24), Error);
}

TEST(Extract, EverySharedCmuWalkingTrial) {
  LEGWORK_REQUIRE_SHARED_CMU();
  int trials = 0, steady = 0;
  double plain_worst = 0, styled_worst = 0;
  for (const auto& e : std::filesystem::directory_iterator(testdata::shared_cmu() / "bvh" / "walking")) {
    const std::string name = e.path().filename().string();
    ++trials;
    // 09_12 is "navigate - walk forward, backward, sideways": events only.
    // 105_xx are stylised walks (macho, lavish, hurt leg...): looser bound.
    const bool styled = name.rfind("105_", 0) == 0;
    const double bound = name == "09_12.bvh" ? 1e9 : styled ? 75.0 : 25.0;
    const double r = check_trial(e.path(), bound);
    if (r < 0) continue;
    ++steady;
    if (name == "09_12.bvh") continue;
    (styled ? styled_worst : plain_worst) = std::max(styled ? styled_worst : plain_worst, r);
  }
  std::printf("[walkcycle] %d shared walking trials, %d with a steady walk; worst resynthesis mean: plain %.1f mm, stylised %.1f mm\n",
              trials, steady, plain_worst, styled_worst);
  EXPECT_EQ(trials, 57);
  EXPECT_GE(steady, 54);  // 16_27 (90-degree turn) and 16_33 (walk, stop) have too few steady steps
}
