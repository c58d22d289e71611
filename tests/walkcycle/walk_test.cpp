// Walking along paths (offline/walk.cpp): no slip straight and curved, the
// stop, reproducibility, retiming.
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
using namespace legwork::walkcycle::testing;

TEST(Walk, StanceFootDoesNotSlipStraightOrCurved) {
  for (const auto& w : kWalks) {
    const CycleModel m = shipped(w);
    const double L = step_length(m);
    EXPECT_GT(L, 0.3) << w;
    const WalkResult straight = walk_path(m, straight_path(8.0));
    const SlipReport s1 = measure_stance_slip(m, straight.motion, straight.labels);
    const WalkResult curved = walk_path(m, quarter_turn());
    const SlipReport s2 = measure_stance_slip(m, curved.motion, curved.labels);
    std::printf("[walkcycle] %-13s step %.3f m | straight 8 m: %d steps, slip max %.2e mm | 90-degree path: %d steps, turned %.1f deg, "
                "slip max %.2e mm, deviation %.3f m, end %.3f m\n",
                w.c_str(), L, straight.steps, s1.max_mm, curved.steps, rad2deg(curved.turning), s2.max_mm,
                curved.max_path_deviation, curved.end_distance);
    EXPECT_LE(s1.max_mm, 1.0) << w;
    EXPECT_LE(s2.max_mm, 2.0) << w;
    EXPECT_GT(s1.phases, 10) << w;
    // It really walks: 8 m forward along +z; the curved walk turns by about 90 degrees.
    const Vec3 end1 = straight.motion.frame(straight.motion.frame_count() - 1).translations[0];
    EXPECT_NEAR(end1.z(), 8.0, L) << w;
    EXPECT_NEAR(std::abs(rad2deg(curved.turning)), 90.0, 12.0) << w;
    EXPECT_LT(curved.end_distance, L) << w;
    EXPECT_LT(curved.max_path_deviation, 0.15) << w;
    EXPECT_LT(straight.max_path_deviation, 0.12) << w;
  }
}

TEST(Walk, SlipMeasureCatchesASlidingFoot) {
  // The same cycle pushed forward at constant speed (no pivoting) slides.
  const CycleModel m = shipped("normal");
  const double L = step_length(m);
  Motion naive = bake_cycle(m);
  Motion longer(m.skeleton, m.fps, 0);
  std::vector<FrameLabel> labels;
  for (int f = 0; f < 3 * m.frames_per_cycle; ++f) {
    Pose p(m.skeleton);
    sample_cycle(m, f, p.ref());
    p.translations[0].z() += L * f / m.half_cycle();
    longer.push_back(p);
    const StanceAt s = stance_at(m, std::max(0.0, f - 0.5));
    labels.push_back({s.step, s.left, s.pivot, false});
  }
  const SlipReport r = measure_stance_slip(m, longer, labels);
  std::printf("[walkcycle] constant-speed root (no pivoting): slip max %.1f mm\n", r.max_mm);
  EXPECT_GT(r.max_mm, 10.0);
}

TEST(Walk, StopsInTheStandingPose) {
  const CycleModel m = shipped("normal");
  const WalkResult w = walk_path(m, straight_path(5.0));
  const int last = w.motion.frame_count() - 1;
  const auto pose = w.motion.frame(last);
  for (int j = 1; j < m.skeleton.joint_count(); ++j)
    EXPECT_LT(rotation_distance(pose.rotations[static_cast<std::size_t>(j)], m.stand.rotations[static_cast<std::size_t>(j)]), 1e-9);
  // Both feet on the floor, side by side.
  const auto pos = joint_positions(m.skeleton, pose);
  const Vec3 la = pos[static_cast<std::size_t>(m.left.ankle)], ra = pos[static_cast<std::size_t>(m.right.ankle)];
  EXPECT_LT(std::abs(la.z() - ra.z()), 0.1);
  EXPECT_TRUE(w.labels.back().stopping);
}

TEST(Walk, SameInputSameBytes) {
  const CycleModel m1 = shipped("double-bounce");
  const CycleModel m2 = shipped("double-bounce");
  const auto a = io::format_bvh(walk_path(m1, quarter_turn(), {}).motion);
  const auto b = io::format_bvh(walk_path(m2, quarter_turn(), {}).motion);
  EXPECT_EQ(a, b);
  EXPECT_GT(a.size(), 10000u);
  EXPECT_EQ(format_walk_keys(read_walk_keys(walk_file("sneak"), cmu_skeleton()), cmu_skeleton()),
            format_walk_keys(read_walk_keys(walk_file("sneak"), cmu_skeleton()), cmu_skeleton()));
}

TEST(Walk, RetimeKeepsThePhaseOfTheKeys) {
  const auto& s = cmu_skeleton();
  const auto keys = read_walk_keys(walk_file("normal"), s);
  const CycleModel m24 = build_cycle(s, keys);
  const CycleModel m32 = build_cycle(s, retime(keys, 32));
  EXPECT_EQ(m32.frames_per_cycle, 32);
  EXPECT_DOUBLE_EQ(m32.key_frames[2], 8.0);
  EXPECT_NEAR(step_length(m24), step_length(m32), 1e-3);  // same poses, same stride
}
