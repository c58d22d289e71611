// Mirroring about the sagittal plane (src/core/mirror.cpp) on real CMU motion.
#include <legwork/core/fk.hpp>
#include <legwork/core/mirror.hpp>

#include "core_samples.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace legwork;


TEST(Mirror, TwiceIsIdentity) {
  Motion m = testdata::walk();
  Motion mm = mirror_motion(mirror_motion(m));
  for (int f = 0; f < m.frame_count(); f += 7)
    for (int j = 0; j < m.joint_count(); ++j) {
      const auto ju = static_cast<std::size_t>(j);
      EXPECT_LT(testdata::quat_distance(mm.frame(f).rotations[ju], m.frame(f).rotations[ju]), 1e-15);
      EXPECT_LT((mm.frame(f).translations[ju] - m.frame(f).translations[ju]).norm(), 1e-15);
    }
}

TEST(Mirror, MirroredLeftHandFollowsReflectedRightHand) {
  Motion m = testdata::walk();
  Motion mir = mirror_motion(m);
  const auto& r = m.skeleton.roles;
  auto p = joint_positions(m), q = joint_positions(mir);
  const auto n = static_cast<std::size_t>(m.joint_count());
  for (int f = 0; f < m.frame_count(); f += 5) {
    const auto base = static_cast<std::size_t>(f) * n;
    Vec3 right = p[base + static_cast<std::size_t>(r[Role::RightHand])];
    Vec3 mirrored_left = q[base + static_cast<std::size_t>(r[Role::LeftHand])];
    EXPECT_LT((mirrored_left - mirror_vector(right)).norm(), 1e-9) << "frame " << f;
    // Central joints stay on the reflected path of themselves.
    Vec3 head = p[base + static_cast<std::size_t>(r[Role::Head])];
    EXPECT_LT((q[base + static_cast<std::size_t>(r[Role::Head])] - mirror_vector(head)).norm(), 1e-9);
  }
}

TEST(Mirror, MirroredWalkStillWalksForward) {
  Motion m = testdata::walk();
  Motion mir = mirror_motion(m);
  const Vec3 d0 = m.frame(m.frame_count() - 1).translations[0] - m.frame(0).translations[0];
  const Vec3 d1 = mir.frame(mir.frame_count() - 1).translations[0] - mir.frame(0).translations[0];
  EXPECT_NEAR(d0.z(), d1.z(), 1e-12);
  EXPECT_NEAR(d0.x(), -d1.x(), 1e-12);
}

TEST(Mirror, RotationIsTheReflectionConjugatedMatrix) {
  // Reflecting x -> -x turns a rotation matrix R into S R S with S = diag(-1, 1, 1).
  const Eigen::Matrix3d S = Vec3(-1, 1, 1).asDiagonal();
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  for (int i = 0; i < 50; ++i) {
    const Quat q = Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
    EXPECT_LT((mirror_rotation(q).toRotationMatrix() - S * q.toRotationMatrix() * S).norm(), 1e-12);
    const Vec3 v(g(rng), g(rng), g(rng));
    EXPECT_LT((mirror_vector(v) - S * v).norm(), 1e-15);
    // Reflection commutes with rotating a vector.
    EXPECT_LT((mirror_rotation(q) * mirror_vector(v) - mirror_vector(q * v)).norm(), 1e-12);
  }
}

TEST(Mirror, PoseTakesTheCounterpartJointsValues) {
  const Motion m = testdata::walk();
  const auto& s = m.skeleton;
  Pose out(s);
  mirror_pose(s, m.frame(40), out.ref());
  const Motion whole = mirror_motion(m);
  for (int j = 0; j < s.joint_count(); ++j) {
    const auto ju = static_cast<std::size_t>(j);
    const auto other = static_cast<std::size_t>(s.mirror[ju]);
    EXPECT_EQ(out.translations[ju], mirror_vector(m.frame(40).translations[other])) << s.names[ju];
    EXPECT_LT(testdata::quat_distance(out.rotations[ju], mirror_rotation(m.frame(40).rotations[other])), 1e-15) << s.names[ju];
    EXPECT_EQ(out.translations[ju], whole.frame(40).translations[ju]);
  }
  // The left knee's mirror image is the right knee's.
  const auto lk = static_cast<std::size_t>(s.roles[Role::LeftKnee]);
  EXPECT_EQ(s.mirror[lk], s.roles[Role::RightKnee]);
  EXPECT_EQ(whole.frame_count(), m.frame_count());
  EXPECT_EQ(whole.fps, m.fps);
}
