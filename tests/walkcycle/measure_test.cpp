// Walk measures (offline/measure.cpp): arc smoothness flags a jerky key.
#include <legwork/core/fk.hpp>
#include <legwork/core/mirror.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/measure.hpp>

#include "testdata.hpp"
#include "walk_samples.hpp"

#include <cstdio>

using namespace legwork;
using namespace legwork::walkcycle;
using namespace legwork::walkcycle::samples;

TEST(Arcs, AJerkyKeyPoseShowsInTheArc) {
  const auto& s = cmu_skeleton();
  auto keys = read_walk_keys(walk_file("normal"), s);
  keys.shift.clear();
  keys.floor_clamp = false;  // the arm alone
  const CycleModel smooth = build_cycle(s, keys);
  // Flick the left elbow at the down key only.
  keys.keys[1].set(s.find("LeftForeArm"), euler_xyz_to_quat(Vec3(0, -95, 0), keys.euler));
  const CycleModel jerky = build_cycle(s, keys);
  const auto a = arc_smoothness(trace_arc(smooth, s.find("LeftHand"), 4));
  const auto b = arc_smoothness(trace_arc(jerky, s.find("LeftHand"), 4));
  std::printf("[walkcycle] LeftHand arc jerk ratio: smooth %.2f, jerky key %.2f (at frame %.1f)\n", a.jerk_ratio, b.jerk_ratio, b.jerk_frame);
  EXPECT_GT(b.jerk_ratio, a.jerk_ratio * 1.3);
  EXPECT_NEAR(b.jerk_frame, keys.key_frames[1], 2.0);
}

