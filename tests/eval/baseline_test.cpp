// The IK baseline over a clip (src/eval/baseline.cpp), driven by the head and
// hands of a real CMU walk on its own skeleton.
#include <legwork/eval/run.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/tracker.hpp>

#include "cmu_sample.hpp"

#include <gtest/gtest.h>

using namespace legwork;

namespace {

Motion walk90() { return resample(testdata::load_sample("cmu/bvh/walking/07_01.bvh"), 90.0); }

// Head and hands only: what a headset and two controllers give.
std::vector<TrackerFrame> headset_frames(const Motion& m) {
  auto frames = tracker_frames_from_motion(m);
  for (auto& f : frames) f.foot(kLeft).valid = f.foot(kRight).valid = false;
  return frames;
}

bool same_frame(ConstPoseRef a, ConstPoseRef b) {
  for (std::size_t j = 0; j < a.rotations.size(); ++j)
    if (a.rotations[j].coeffs() != b.rotations[j].coeffs() || a.translations[j] != b.translations[j]) return false;
  return true;
}

}  // namespace

TEST(IkBaseline, OneFramePerInputWithTheHeadOnTheHeadsetAndHandsOnTheControllers) {
  const Motion m = walk90();
  const auto frames = headset_frames(m);
  const Motion out = eval::run_ik_baseline(m.skeleton, frames, m.fps);
  ASSERT_EQ(out.frame_count(), static_cast<int>(frames.size()));
  EXPECT_EQ(out.fps, m.fps);
  EXPECT_EQ(out.skeleton.names, m.skeleton.names);
  const auto& r = m.skeleton.roles;
  std::vector<Transform> g(static_cast<std::size_t>(m.joint_count()));
  double hand_err = 0;
  for (int f = 0; f < out.frame_count(); ++f) {
    forward_kinematics(out.skeleton, out.frame(f), g);
    const auto& in = frames[static_cast<std::size_t>(f)];
    EXPECT_LT((g[static_cast<std::size_t>(r[Role::Head])].translation - in.head().position).norm(), 1e-6) << "frame " << f;
    for (int side : {kLeft, kRight}) {
      const int hand = r[side == kLeft ? Role::LeftHand : Role::RightHand];
      hand_err += (g[static_cast<std::size_t>(hand)].translation - in.hand(side).position).norm();
    }
  }
  // The controllers are where this very skeleton's wrists were: within reach, so
  // the two-bone arms put the wrists on them (mean under 5 mm, as the IK promises).
  EXPECT_LT(hand_err / (2.0 * out.frame_count()), 0.005);
}

TEST(IkBaseline, ARejectedFrameRepeatsTheLastPose) {
  const Motion m = trim(walk90(), 0, 39);
  auto frames = headset_frames(m);
  frames[20].time = frames[19].time;  // not after the last frame: rejected
  const Motion out = eval::run_ik_baseline(m.skeleton, frames, m.fps);
  ASSERT_EQ(out.frame_count(), 40);
  EXPECT_TRUE(same_frame(out.frame(20), out.frame(19)));
  EXPECT_FALSE(same_frame(out.frame(21), out.frame(20)));  // the next good frame moves on
}

TEST(IkBaseline, SolverTimeIsAddedToTheCallersTotal) {
  const Motion m = trim(walk90(), 0, 29);
  const auto frames = headset_frames(m);
  double seconds = 5.0;
  (void)eval::run_ik_baseline(m.skeleton, frames, m.fps, &seconds);
  EXPECT_GT(seconds, 5.0);
  EXPECT_LT(seconds, 5.0 + 60.0);
  EXPECT_EQ(eval::run_ik_baseline(m.skeleton, {}, m.fps).frame_count(), 0);
}

TEST(IkBaseline, ASkeletonWithoutArmsIsRefusedByName) {
  Skeleton s;
  s.add_joint("Hips", -1, Vec3::Zero());
  s.add_joint("Head", 0, Vec3(0, 0.6, 0));
  resolve_roles(s);
  const auto frames = headset_frames(trim(walk90(), 0, 9));
  try {
    (void)eval::run_ik_baseline(s, frames, 90.0);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("full-body IK: the skeleton has no joint for role(s)", 0), 0u) << e.what();
  }
}

// The fair baseline (method "ik"): another subject's skeleton scaled to the
// user's standing height, as the engine's database skeleton is; the output
// stands as tall as the user, keeps the reference's proportions, and differs
// from the baseline on the user's own bone lengths.
TEST(IkBaseline, AtHeightRunsOnTheReferenceScaledToTheUsersHeight) {
  const Motion user = walk90();  // subject 7
  const Skeleton reference = testdata::load_sample("cmu/bvh/basketball/124_03.bvh").skeleton;  // subject 124
  const double h_user = measure_body(user.skeleton).standing_height, h_ref = measure_body(reference).standing_height;
  ASSERT_GT(std::abs(h_user - h_ref), 0.01) << "the two subjects must differ in height for this test";
  const Motion fair = eval::run_ik_baseline_at_height(reference, user);
  const Motion own = eval::run_ik_baseline(user);
  ASSERT_EQ(fair.frame_count(), user.frame_count());
  EXPECT_EQ(fair.skeleton.names, reference.names);
  EXPECT_NEAR(measure_body(fair.skeleton).standing_height, h_user, 1e-9);
  const int thigh = fair.skeleton.roles[Role::LeftKnee];
  const double ratio = fair.skeleton.rest_offsets[static_cast<std::size_t>(thigh)].norm() /
                       reference.rest_offsets[static_cast<std::size_t>(thigh)].norm();
  EXPECT_NEAR(ratio, h_user / h_ref, 1e-9);
  // The head still follows the headset on the scaled reference skeleton.
  std::vector<Transform> world(static_cast<std::size_t>(fair.skeleton.joint_count()));
  std::vector<Transform> truth(static_cast<std::size_t>(user.skeleton.joint_count()));
  const int head = fair.skeleton.roles[Role::Head];
  double worst = 0;
  for (int f = 0; f < fair.frame_count(); f += 10) {
    forward_kinematics(fair.skeleton, fair.frame(f), world);
    forward_kinematics(user.skeleton, user.frame(f), truth);
    worst = std::max(worst, (world[static_cast<std::size_t>(head)].translation -
                             truth[static_cast<std::size_t>(user.skeleton.roles[Role::Head])].translation).norm());
  }
  EXPECT_LT(worst, 0.02);
  // Not the own-skeleton run under another name.
  forward_kinematics(fair.skeleton, fair.frame(fair.frame_count() / 2), world);
  std::vector<Transform> own_world(static_cast<std::size_t>(own.skeleton.joint_count()));
  forward_kinematics(own.skeleton, own.frame(own.frame_count() / 2), own_world);
  const Vec3 d = world[static_cast<std::size_t>(fair.skeleton.roles[Role::LeftAnkle])].translation -
                 own_world[static_cast<std::size_t>(own.skeleton.roles[Role::LeftAnkle])].translation;
  EXPECT_GT(d.norm(), 1e-4);
}
