// Forward kinematics (src/core/fk.cpp) on real CMU motion and on chains whose
// joint positions are known in closed form.
#include <legwork/core/fk.hpp>

#include "cmu_sample.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace legwork;

namespace {
Motion walk() { return testdata::load_sample("cmu/bvh/walking/07_01.bvh"); }
double quat_distance(const Quat& a, const Quat& b) { return 1.0 - std::abs(a.dot(b)); }

// A planar chain of n unit bones along the parent's x axis, each joint turned
// by theta about z: joint k sits at sum_{i<k} (cos(i theta), sin(i theta)).
Skeleton planar_chain(int n) {
  Skeleton s;
  s.add_joint("j0", -1, Vec3::Zero());
  for (int k = 1; k < n; ++k) s.add_joint("j" + std::to_string(k), k - 1, Vec3::UnitX());
  return s;
}
Pose bent(const Skeleton& s, double theta) {
  Pose p(s);
  for (auto& r : p.rotations) r = Quat(Eigen::AngleAxisd(theta, Vec3::UnitZ()));
  return p;
}
Vec3 planar_chain_position(int k, double theta) {
  Vec3 v = Vec3::Zero();
  for (int i = 1; i <= k; ++i) v += Vec3(std::cos(i * theta), std::sin(i * theta), 0);
  return v;
}
}  // namespace

TEST(ForwardKinematics, MatchesChainedTransformsAndBatch) {
  Motion m = walk();
  const auto& s = m.skeleton;
  std::vector<Transform> g(static_cast<std::size_t>(s.joint_count()));
  forward_kinematics(s, m.frame(10), g);
  // Oracle: walk from the joint to the root composing transforms explicitly.
  for (int j = 0; j < s.joint_count(); ++j) {
    Transform t;
    for (int k = j; k >= 0; k = s.parents[static_cast<std::size_t>(k)]) {
      Transform local{m.frame(10).rotations[static_cast<std::size_t>(k)], m.frame(10).translations[static_cast<std::size_t>(k)]};
      t = local * t;
    }
    EXPECT_LT((t.translation - g[static_cast<std::size_t>(j)].translation).norm(), 1e-12);
    EXPECT_LT(quat_distance(t.rotation, g[static_cast<std::size_t>(j)].rotation), 1e-12);
  }
  auto all = joint_positions(m);
  const auto n = static_cast<std::size_t>(s.joint_count());
  for (std::size_t j = 0; j < n; ++j) EXPECT_LT((all[10 * n + j] - g[j].translation).norm(), 1e-12);
}

// After a change inside one subtree (frame 10's neck and arm rotations put
// into frame 40), redoing that subtree gives what a whole FK gives; a joint
// outside it is left as it was, even when its entry is stale.
TEST(ForwardKinematics, ASubtreeRedoneEqualsTheWholeAndLeavesTheRestAlone) {
  Motion m = walk();
  const auto& s = m.skeleton;
  const auto n = static_cast<std::size_t>(s.joint_count());
  const int neck = s.find("Neck"), clavicle = s.find("LeftShoulder"), hand = s.find("LeftHand"), foot = s.find("RightFoot");
  ASSERT_GE(neck, 0);
  ASSERT_GE(clavicle, 0);
  ASSERT_GE(hand, 0);
  ASSERT_GE(foot, 0);
  std::vector<Transform> whole(n), part(n);
  for (int root : {neck, clavicle}) {
    Pose p(s);
    const ConstPoseRef f40 = m.frame(40);
    p.rotations.assign(f40.rotations.begin(), f40.rotations.end());
    p.translations.assign(f40.translations.begin(), f40.translations.end());
    forward_kinematics(s, p.ref(), part);
    std::vector<bool> inside(n, false);
    for (int j = 0; j < s.joint_count(); ++j) {
      const int parent = s.parents[static_cast<std::size_t>(j)];
      inside[static_cast<std::size_t>(j)] = j == root || (parent >= 0 && inside[static_cast<std::size_t>(parent)]);
      if (inside[static_cast<std::size_t>(j)]) p.rotations[static_cast<std::size_t>(j)] = m.frame(10).rotations[static_cast<std::size_t>(j)];
    }
    const Transform stale{Quat(0, 1, 0, 0), Vec3(9, 9, 9)};
    part[static_cast<std::size_t>(foot)] = stale;
    forward_kinematics_subtree(s, p.ref(), root, part);
    forward_kinematics(s, p.ref(), whole);
    int redone = 0;
    for (std::size_t j = 0; j < n; ++j) {
      if (j == static_cast<std::size_t>(foot)) continue;
      EXPECT_LT((part[j].translation - whole[j].translation).norm(), 1e-12) << s.names[j];
      EXPECT_LT(quat_distance(part[j].rotation, whole[j].rotation), 1e-12) << s.names[j];
      redone += inside[j];
    }
    EXPECT_TRUE(inside[static_cast<std::size_t>(root == neck ? s.find("Head") : hand)]);
    EXPECT_GE(redone, 3);
    EXPECT_EQ(part[static_cast<std::size_t>(foot)].translation, stale.translation);  // outside: untouched
  }
}

TEST(ForwardKinematics, LocalFromModelInvertsFk) {
  Motion m = walk();
  const auto& s = m.skeleton;
  const auto n = static_cast<std::size_t>(s.joint_count());
  std::vector<Transform> g(n);
  forward_kinematics(s, m.frame(50), g);
  std::vector<Quat> model(n), local(n);
  for (std::size_t j = 0; j < n; ++j) model[j] = g[j].rotation;
  local_from_model_rotations(s, model, local);
  for (std::size_t j = 0; j < n; ++j) EXPECT_LT(quat_distance(local[j], m.frame(50).rotations[j]), 1e-12);
}

TEST(ForwardKinematics, WalkingFeetStartNearTheFloor) {
  Motion m = walk();
  const auto& r = m.skeleton.roles;
  auto p = joint_positions(m);
  double floor = 1e9;
  for (const auto& v : p) floor = std::min(floor, v.y());
  const double lf = p[static_cast<std::size_t>(r[Role::LeftToe])].y(), rf = p[static_cast<std::size_t>(r[Role::RightToe])].y();
  EXPECT_LT(std::min(lf, rf) - floor, 0.05);
  const double head = p[static_cast<std::size_t>(r[Role::Head])].y() - floor;
  EXPECT_GT(head, 1.2);
  EXPECT_LT(head, 1.9);
}

TEST(ForwardKinematics, PlanarChainLandsOnTheClosedFormPositions) {
  // 200 joints: longer than forward_positions' stack buffer (128), so its heap path runs too.
  for (int n : {5, 200}) {
    const Skeleton s = planar_chain(n);
    const double theta = 0.05;
    const Pose p = bent(s, theta);
    const auto pos = joint_positions(s, p);
    std::vector<Transform> g(static_cast<std::size_t>(n));
    forward_kinematics(s, p, g);
    for (int k = 0; k < n; ++k) {
      const auto ku = static_cast<std::size_t>(k);
      EXPECT_LT((pos[ku] - planar_chain_position(k, theta)).norm(), 1e-9) << n << " joints, joint " << k;
      EXPECT_LT((g[ku].translation - pos[ku]).norm(), 1e-9);
      EXPECT_LT(quat_distance(g[ku].rotation, Quat(Eigen::AngleAxisd((k + 1) * theta, Vec3::UnitZ()))), 1e-12);
    }
  }
}

TEST(ForwardKinematics, BatchedTransformsEqualPerFrameAndKeepBoneLengths) {
  const Motion m = walk();
  const auto& s = m.skeleton;
  const auto n = static_cast<std::size_t>(m.joint_count());
  std::vector<Transform> all(static_cast<std::size_t>(m.frame_count()) * n), one(n);
  forward_kinematics(m, all);
  for (int f = 0; f < m.frame_count(); f += 37) {
    forward_kinematics(s, m.frame(f), one);
    for (std::size_t j = 0; j < n; ++j) {
      const Transform& b = all[static_cast<std::size_t>(f) * n + j];
      EXPECT_EQ(b.translation, one[j].translation);
      // A rigid chain: each joint stays its rest-offset length from its parent.
      const int p = s.parents[j];
      if (p < 0) continue;
      EXPECT_NEAR((b.translation - all[static_cast<std::size_t>(f) * n + static_cast<std::size_t>(p)].translation).norm(),
                  m.frame(f).translations[j].norm(), 1e-9);
    }
  }
}

TEST(ForwardKinematics, EndSiteSitsAtItsOffsetFromTheJoint) {
  const Motion m = walk();
  const auto& s = m.skeleton;
  std::vector<Transform> g(static_cast<std::size_t>(s.joint_count()));
  forward_kinematics(s, m.frame(20), g);
  int with = 0, without = 0;
  for (int j = 0; j < s.joint_count(); ++j) {
    const auto ju = static_cast<std::size_t>(j);
    const Vec3 tip = end_site_position(s, g, j);
    if (s.has_end_site[ju]) {
      ++with;
      EXPECT_NEAR((tip - g[ju].translation).norm(), s.end_sites[ju].norm(), 1e-9) << s.names[ju];
      EXPECT_LT((g[ju].rotation.conjugate() * (tip - g[ju].translation) - s.end_sites[ju]).norm(), 1e-9);
    } else {
      ++without;
      EXPECT_EQ(tip, g[ju].translation) << s.names[ju];
    }
  }
  EXPECT_GT(with, 0);  // the CMU rig has End Sites at the head, hands and toes
  EXPECT_GT(without, 0);
}
