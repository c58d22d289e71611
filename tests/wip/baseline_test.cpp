// The key-frame baseline (src/wip/baseline.cpp): a walk cycle cut from a real
// CMU walk, cross-faded with an idle pose by the walking decisions.
#include <legwork/wip/baseline.hpp>
#include <legwork/wip/offline/walk_cycle.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/mirror.hpp>

#include "cmu_sample.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace legwork::wip {
namespace {

Motion walk() { return testdata::load_sample("cmu/bvh/walking/07_01.bvh"); }
const Motion& cycle() {
  static const Motion c = extract_walk_cycle(walk());
  return c;
}

TEST(KeyframeBaseline, AnkleDepthsAreRelativeToThePelvis) {
  const Motion m = trim(walk(), 0, 199);
  const auto left = ankle_depths(m, kLeft), right = ankle_depths(m, kRight);
  ASSERT_EQ(left.size(), 200u);
  // Carrying the whole body 5 m forward moves no ankle relative to the pelvis.
  Motion ahead = m;
  for (int f = 0; f < ahead.frame_count(); ++f) ahead.frame(f).translations[0] += Vec3(0, 0, 5);
  const auto moved = ankle_depths(ahead, kLeft);
  for (std::size_t f = 0; f < left.size(); ++f) EXPECT_NEAR(moved[f], left[f], 1e-9);
  // Mirroring (x -> -x) leaves depth alone and swaps the feet.
  const auto mirrored_left = ankle_depths(mirror_motion(m), kLeft);
  for (std::size_t f = 0; f < left.size(); ++f) EXPECT_NEAR(mirrored_left[f], right[f], 1e-9);
  // A stride puts the feet on both sides of the pelvis.
  EXPECT_LT(*std::min_element(left.begin(), left.end()), 0.0);
  EXPECT_GT(*std::max_element(left.begin(), left.end()), 0.0);
}

TEST(KeyframeBaseline, ModelScalesTheDepthsToTheAvatarsLegAndStandsAtTheMeanHeight) {
  const Motion& c = cycle();
  const double clip_leg = measure_body(c.skeleton).leg_length;
  const KeyframeBaselineModel m = make_keyframe_baseline(c, 2 * clip_leg);
  for (int foot : {kLeft, kRight}) {
    const auto raw = ankle_depths(c, foot);
    ASSERT_EQ(m.depth[foot].size(), raw.size());
    for (std::size_t f = 0; f < raw.size(); ++f) EXPECT_NEAR(m.depth[foot][f], 2 * raw[f], 1e-12);
  }
  double mean_y = 0;
  for (int f = 0; f < c.frame_count(); ++f) mean_y += c.frame(f).translations[0].y() / c.frame_count();
  EXPECT_NEAR(m.idle.translations[0].y(), mean_y, 1e-12);
  EXPECT_EQ(m.idle.translations[0].x(), 0.0);
  EXPECT_EQ(m.idle.translations[0].z(), 0.0);
  for (std::size_t j = 1; j < m.idle.translations.size(); ++j) EXPECT_EQ(m.idle.translations[j], c.skeleton.rest_offsets[j]);
}

TEST(KeyframeBaseline, ACycleOfFewerThanTwoFramesIsAnError) {
  try {
    (void)make_keyframe_baseline(trim(cycle(), 0, 0), 0.9);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "key-frame baseline: the walk cycle has fewer than 2 frames");
  }
}

TEST(KeyframeBaseline, StoppedItStandsIdle) {
  const KeyframeBaselineModel m = make_keyframe_baseline(cycle(), 0.9);
  KeyframeBaselineState s = make_baseline_state(m);
  for (int i = 0; i < 50; ++i) update_baseline(m, false, 1.0 / 90, s);
  EXPECT_EQ(s.weight, 0.0);
  EXPECT_EQ(s.clip_time, 0.0);
  EXPECT_EQ(s.z[0], 0.0);
  EXPECT_EQ(s.z[1], 0.0);
  for (std::size_t j = 0; j < s.pose.translations.size(); ++j) EXPECT_LT((s.pose.translations[j] - m.idle.translations[j]).norm(), 1e-12);
}

TEST(KeyframeBaseline, WalkingFadesInExponentiallyAndPlaysTheCycleInStep) {
  const KeyframeBaselineModel m = make_keyframe_baseline(cycle(), 0.9);
  KeyframeBaselineState s = make_baseline_state(m);
  const double dt = 1.0 / m.clip.fps;  // one clip frame per update
  const int n = m.clip.frame_count();
  for (int i = 1; i <= 3 * n + 7; ++i) {
    update_baseline(m, true, dt, s);
    // First-order cross-fade: after time t, 1 - exp(-t / tau) of the way to walking.
    EXPECT_NEAR(s.weight, 1 - std::exp(-i * dt / m.blend_tau), 1e-9) << "update " << i;
    const int frame = i % n;  // the cycle loops: frame n is frame 0 again
    for (int foot : {kLeft, kRight})
      EXPECT_NEAR(s.z[foot], s.weight * m.depth[foot][static_cast<std::size_t>(frame)], 1e-6) << "update " << i;
  }
  // Fully faded in, the pose is the clip's frame (the idle's share is below 1e-9).
  const int frame = (3 * n + 7) % n;
  for (std::size_t j = 0; j < s.pose.translations.size(); ++j)
    EXPECT_LT((s.pose.translations[j] - m.clip.frame(frame).translations[j]).norm(), 1e-6) << "joint " << j;
  // Stopping fades back out and, once faded, restarts the cycle from its first frame.
  for (int i = 0; i < 200 && s.clip_time != 0; ++i) update_baseline(m, false, dt, s);
  EXPECT_EQ(s.clip_time, 0.0);
  EXPECT_LE(s.weight, 1e-3);
}

}  // namespace
}  // namespace legwork::wip
