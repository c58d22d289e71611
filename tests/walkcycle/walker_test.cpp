// Runtime walker: steered frame by frame, it keeps the stance foot planted,
// turns towards the asked heading at most max_turn_per_step per step, and a
// straight walk matches the offline generator's stride.
#include <legwork/io/bvh.hpp>
#include <legwork/walkcycle/measure.hpp>
#include <legwork/walkcycle/walker.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <cstdio>

using namespace legwork;
using namespace legwork::walkcycle;

namespace {
CycleModel model(const std::string& name) {
  const Skeleton& s = testdata::sample_skeleton();
  return build_cycle(s, read_walk_keys(testdata::walk_keys_file(name), s));
}
}  // namespace

TEST(Walker, SteeredLiveWithoutSlip) {
  for (const char* w : {"normal", "sneak", "double-bounce"}) {
    const CycleModel m = model(w);
    WalkerState s;
    Pose pose(m.skeleton);
    Motion rec(m.skeleton, 30.0, 0);
    std::vector<FrameLabel> labels;
    walker_reset(m, s, Vec3(1, 0, 2), 0.0, pose.ref());
    rec.push_back(pose);
    labels.push_back({0, true, Pivot::Heel, false});
    const double dt = 1.0 / 30.0;
    const int frames = 300;  // 10 s: straight, then asked to face +x (90 degrees left)
    for (int f = 1; f < frames; ++f) {
      const double t_prev = s.time;
      walker_update(m, s, dt, f < 100 ? 0.0 : kPi / 2, pose.ref());
      rec.push_back(pose);
      const StanceAt st = stance_at(m, 0.5 * (t_prev + s.time));
      labels.push_back({st.step, st.left, st.pivot, false});
    }
    const SlipReport slip = measure_stance_slip(m, rec, labels);
    const Vec3 end = rec.frame(frames - 1).translations[0];
    std::printf("[walkcycle] walker %-13s 10 s steered: slip max %.2e mm, heading %.1f deg, end (%.2f, %.2f)\n", w, slip.max_mm,
                rad2deg(s.heading), end.x(), end.z());
    EXPECT_LE(slip.max_mm, 1e-6) << w;
    EXPECT_NEAR(s.heading, kPi / 2, 1e-9) << w;  // reached, in steps of at most 30 degrees
    EXPECT_GT(end.x(), 2.0) << w;                   // walked off to the left (+x)
    // The first 3 s are straight: the stride matches the offline generator's.
    const double straight_steps = 3.0 * m.fps / m.half_cycle();
    const double z3 = rec.frame(90).translations[0].z() - 2.0;
    EXPECT_NEAR(z3, straight_steps * step_length(m), 0.6 * step_length(m)) << w;
  }
}

TEST(Walker, TurnIsLimitedPerStep) {
  const CycleModel m = model("normal");
  WalkerState s;
  s.max_turn_per_step = deg2rad(20);
  Pose pose(m.skeleton);
  walker_reset(m, s, Vec3::Zero(), 0.0, pose.ref());
  double last = 0, fastest = 0;
  for (int f = 0; f < 48; ++f) {
    walker_update(m, s, 1.0 / m.fps, kPi, pose.ref());  // asked to turn right round
    EXPECT_LE(std::abs(s.heading_to - s.heading_from), deg2rad(20) + 1e-12);
    fastest = std::max(fastest, std::abs(s.heading - last));
    last = s.heading;
  }
  // 48 frames = 4 steps of 12: four headings latched at the mid-steps, 20 degrees each.
  EXPECT_EQ(s.decided_step, 4);
  EXPECT_NEAR(std::abs(s.heading_to), deg2rad(80), 1e-9);
  // Blended over a step (smoothstep, peak slope 1.5): at most 20 * 1.5 / 12 degrees per frame.
  EXPECT_LE(fastest, deg2rad(20) * 1.5 / 12 + 1e-9);
}
