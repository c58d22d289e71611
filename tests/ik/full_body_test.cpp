// Full-body IK baseline driven by real CMU head and hand tracks.
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/ik/full_body.hpp>
#include <legwork/io/bvh.hpp>

#include <gtest/gtest.h>

#include <cmath>

#include "cmu_sample.hpp"
#include "testdata.hpp"

namespace legwork::ik {
namespace {

Motion load90(const std::string& rel) { return resample(testdata::load_sample(rel), 90.0); }

TrackerFrame tracker_of(const Skeleton& s, std::span<const Transform> g) {
  TrackerFrame t;
  const auto at = [&](Role r) { return g[static_cast<std::size_t>(s.roles[r])]; };
  t.head_position = at(Role::Head).translation;
  t.head_rotation = at(Role::Head).rotation;
  t.hand_position = {at(Role::LeftHand).translation, at(Role::RightHand).translation};
  t.hand_rotation = {at(Role::LeftHand).rotation, at(Role::RightHand).rotation};
  return t;
}

struct IkRun {
  Motion out;
  double head_err = 0, hand_err = 0, max_hand_err = 0, max_head_err = 0;
  double lower_err = 0, full_err = 0;
  int steps = 0;
};

IkRun drive(const Motion& truth) {
  const Skeleton& skel = truth.skeleton;
  FullBodyModel model(skel);
  FullBodyState state(model);
  IkRun r{Motion(skel, truth.fps, truth.frame_count()), 0, 0, 0, 0, 0, 0, 0};
  std::vector<Transform> g(static_cast<std::size_t>(skel.joint_count())), o(g.size());
  int lower_n = 0;
  for (int f = 0; f < truth.frame_count(); ++f) {
    forward_kinematics(skel, truth.frame(f), g);
    const TrackerFrame in = tracker_of(skel, g);
    solve_full_body(model, in, 1.0 / truth.fps, state, r.out.frame(f));
    forward_kinematics(skel, r.out.frame(f), o);
    const auto pos = [&](std::span<const Transform> x, Role role) { return x[static_cast<std::size_t>(skel.roles[role])].translation; };
    const double he = (pos(o, Role::Head) - in.head_position).norm();
    const double le = (pos(o, Role::LeftHand) - in.hand_position[0]).norm();
    const double re = (pos(o, Role::RightHand) - in.hand_position[1]).norm();
    r.head_err += he;
    r.hand_err += 0.5 * (le + re);
    r.max_head_err = std::max(r.max_head_err, he);
    r.max_hand_err = std::max({r.max_hand_err, le, re});
    for (int j = 0; j < skel.joint_count(); ++j) {
      const double e = (o[static_cast<std::size_t>(j)].translation - g[static_cast<std::size_t>(j)].translation).norm();
      EXPECT_TRUE(std::isfinite(e)) << "frame " << f << " joint " << skel.names[static_cast<std::size_t>(j)];
    }
    for (Role role : {Role::Pelvis, Role::LeftKnee, Role::RightKnee, Role::LeftAnkle, Role::RightAnkle}) {
      r.lower_err += (pos(o, role) - pos(g, role)).norm();
      ++lower_n;
    }
  }
  r.head_err /= truth.frame_count();
  r.hand_err /= truth.frame_count();
  r.lower_err /= lower_n;
  r.steps = state.steps_taken;
  return r;
}

TEST(FullBodyIk, HeadExactHandsOnTargetOnAWalk) {
  const Motion truth = load90("cmu/bvh/walking/07_01.bvh");
  const IkRun r = drive(truth);
  EXPECT_LT(r.max_head_err, 1e-6);
  EXPECT_LT(r.hand_err, 0.005);  // mean under 5 mm (exact when within reach)
  // A walk of several metres needs many steps, and the legs stay near the real ones.
  EXPECT_GT(r.steps, 6);
  EXPECT_LT(r.lower_err, 0.25);
  std::printf("07_01: hands %.2f mm mean (max %.1f mm), lower-body joints %.1f cm, %d steps\n", 1000 * r.hand_err,
              1000 * r.max_hand_err, 100 * r.lower_err, r.steps);
}

TEST(FullBodyIk, StandingStillPlantsTheFeetAndCrouchesWhenTheHeadDrops) {
  const Motion walk = load90("cmu/bvh/walking/07_01.bvh");
  const Skeleton& skel = walk.skeleton;
  FullBodyModel model(skel);
  FullBodyState state(model);
  Pose pose(skel);
  std::vector<Transform> g(static_cast<std::size_t>(skel.joint_count()));
  TrackerFrame in;
  const double h0 = model.standing_head_height();
  in.head_position = Vec3(0.3, h0, 1.0);
  in.hand_position = {Vec3(0.55, h0 - 0.55, 1.05), Vec3(0.05, h0 - 0.55, 1.05)};
  Vec3 ankle_start;
  double pelvis_standing = 0;
  for (int f = 0; f < 180; ++f) {
    // Two seconds standing, then the head sinks 40 cm over two seconds.
    const double drop = f < 90 ? 0.0 : 0.4 * (f - 90) / 89.0;
    TrackerFrame x = in;
    x.head_position.y() -= drop;
    for (auto& h : x.hand_position) h.y() -= drop;
    solve_full_body(model, x, 1.0 / 90, state, pose.ref());
    forward_kinematics(skel, pose, g);
    const Vec3 ankle = g[static_cast<std::size_t>(skel.roles[Role::LeftAnkle])].translation;
    if (f == 0) ankle_start = ankle;
    if (f == 89) pelvis_standing = g[static_cast<std::size_t>(skel.roles[Role::Pelvis])].translation.y();
    EXPECT_LT((ankle - ankle_start).norm(), 1e-6) << "frame " << f << ": a planted foot moved";
  }
  EXPECT_EQ(state.steps_taken, 0);
  const double pelvis_low = g[static_cast<std::size_t>(skel.roles[Role::Pelvis])].translation.y();
  EXPECT_LT(pelvis_low, pelvis_standing - 0.25);  // legs folded most of the drop
  // Knees bent: hip-ankle distance well below the leg length.
  const Vec3 hip = g[static_cast<std::size_t>(skel.roles[Role::LeftHip])].translation;
  const Vec3 knee = g[static_cast<std::size_t>(skel.roles[Role::LeftKnee])].translation;
  const Vec3 ankle = g[static_cast<std::size_t>(skel.roles[Role::LeftAnkle])].translation;
  EXPECT_LT((ankle - hip).norm(), 0.9 * ((knee - hip).norm() + (ankle - knee).norm()));
  // The knee bends forward (+z, the facing direction), not backward.
  EXPECT_GT(knee.z() - 0.5 * (hip.z() + ankle.z()), 0.02);
}

TEST(FullBodyIk, NonFiniteSamplesNeverReachThePose) {
  const Motion walk = load90("cmu/bvh/walking/07_01.bvh");
  const Skeleton& skel = walk.skeleton;
  FullBodyModel model(skel);
  FullBodyState state(model);
  std::vector<Transform> g(static_cast<std::size_t>(skel.joint_count()));
  forward_kinematics(skel, walk.frame(10), g);
  const TrackerFrame good = tracker_of(skel, g);
  Pose pose(skel);
  solve_full_body(model, good, 1.0 / 90, state, pose.ref());
  const Pose before = pose;
  TrackerFrame bad = good;
  bad.head_position.x() = std::nan("");
  solve_full_body(model, bad, 1.0 / 90, state, pose.ref());
  for (int j = 0; j < skel.joint_count(); ++j)
    EXPECT_TRUE(pose.rotations[static_cast<std::size_t>(j)].coeffs() == before.rotations[static_cast<std::size_t>(j)].coeffs());
  bad = good;
  bad.hand_position[1] = Vec3::Constant(std::nan(""));  // right controller lost
  solve_full_body(model, bad, 1.0 / 90, state, pose.ref());
  forward_kinematics(skel, pose, g);
  for (const auto& t : g) EXPECT_TRUE(t.translation.allFinite() && t.rotation.coeffs().allFinite());
  // The right wrist hangs below its shoulder.
  EXPECT_LT(g[static_cast<std::size_t>(skel.roles[Role::RightHand])].translation.y(),
            g[static_cast<std::size_t>(skel.roles[Role::RightShoulder])].translation.y() - 0.3);
}

TEST(FullBodyIk, RejectsASkeletonWithoutArms) {
  Skeleton s;
  s.add_joint("Hips", -1, Vec3::Zero());
  s.add_joint("Head", 0, Vec3(0, 0.6, 0));
  resolve_roles(s);
  EXPECT_THROW(FullBodyModel{s}, Error);
}

}  // namespace
}  // namespace legwork::ik
