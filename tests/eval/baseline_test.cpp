// The IK baseline over a clip (src/eval/baseline.cpp), driven by the head and
// hands of a real CMU walk on its own skeleton.
#include <legwork/eval/run.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
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
