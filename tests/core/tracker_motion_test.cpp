// Motion -> tracker frames (src/core/tracker_motion.cpp) on real CMU motion.
#include <legwork/core/fk.hpp>
#include <legwork/core/tracker.hpp>

#include "cmu_sample.hpp"
#include "error_message.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace legwork {
namespace {

Motion walk() { return testdata::load_sample("cmu/bvh/walking/07_01.bvh"); }

std::string error_of(const Motion& m, double rate, std::size_t max_frames) {
  return testdata::message_of([&] { (void)tracker_frames_from_motion(m, rate, max_frames); });
}

// Device d of every frame sits on (and turns with) the joint of its role.
constexpr Role kDeviceRole[kDeviceCount] = {Role::Head, Role::LeftHand, Role::RightHand, Role::LeftAnkle, Role::RightAnkle};

TEST(TrackerMotion, FramesFromARealMotionPlaceDevicesOnTheJoints) {
  const Motion m = walk();
  const auto frames = tracker_frames_from_motion(m);
  ASSERT_EQ(static_cast<int>(frames.size()), m.frame_count());
  for (const auto& f : frames)
    for (const auto& d : f.devices) EXPECT_TRUE(usable(d));
  // The head is above the hands and feet, the feet near the floor.
  EXPECT_GT(frames[10].head().position.y(), frames[10].hand(kLeft).position.y());
  EXPECT_LT(frames[10].foot(kLeft).position.y(), 0.3);
  EXPECT_NEAR(frames[1].time - frames[0].time, 1.0 / m.fps, 1e-12);
  const auto at30 = tracker_frames_from_motion(m, 30.0);
  EXPECT_NEAR(static_cast<double>(at30.size()), m.duration() * 30.0 + 1, 1.0);
  EXPECT_THROW(tracker_frames_from_motion(m, -1.0), Error);
  EXPECT_THROW(tracker_frames_from_motion(m, 1e9), Error);
}

TEST(TrackerMotion, EachDeviceIsItsRoleJointsModelTransform) {
  const Motion m = walk();
  const auto frames = tracker_frames_from_motion(m);
  std::vector<Transform> g(static_cast<std::size_t>(m.joint_count()));
  for (int f = 0; f < m.frame_count(); f += 11) {
    forward_kinematics(m.skeleton, m.frame(f), g);
    EXPECT_DOUBLE_EQ(frames[static_cast<std::size_t>(f)].time, f / m.fps);
    for (int d = 0; d < kDeviceCount; ++d) {
      const auto& dev = frames[static_cast<std::size_t>(f)].devices[static_cast<std::size_t>(d)];
      const auto& joint = g[static_cast<std::size_t>(m.skeleton.roles[kDeviceRole[d]])];
      EXPECT_LT((dev.position - joint.translation).norm(), 1e-12) << "frame " << f << " device " << d;
      EXPECT_LT(dev.rotation.angularDistance(joint.rotation), 1e-9) << "frame " << f << " device " << d;
    }
  }
}

TEST(TrackerMotion, SamplingAtTheMotionsOwnRateGivesTheSameFrames) {
  const Motion m = walk();
  const auto own = tracker_frames_from_motion(m);
  const auto sampled = tracker_frames_from_motion(m, m.fps);
  ASSERT_EQ(sampled.size(), own.size());
  for (std::size_t i = 0; i < own.size(); i += 7) {
    EXPECT_NEAR(sampled[i].time, own[i].time, 1e-12);
    for (int d = 0; d < kDeviceCount; ++d)
      EXPECT_LT((sampled[i].devices[static_cast<std::size_t>(d)].position - own[i].devices[static_cast<std::size_t>(d)].position).norm(), 1e-9)
          << "frame " << i << " device " << d;
  }
  // Times at a given rate step by exactly 1/rate from zero.
  const auto at90 = tracker_frames_from_motion(m, 90.0);
  for (std::size_t i = 0; i < at90.size(); i += 50) EXPECT_DOUBLE_EQ(at90[i].time, static_cast<double>(i) / 90.0);
  EXPECT_LE(at90.back().time, m.duration() + 1e-9);
}

TEST(TrackerMotion, ARoleTheSkeletonLacksLeavesItsDeviceInvalid) {
  Motion m = walk();
  m.skeleton.roles[Role::LeftHand] = -1;
  const auto frames = tracker_frames_from_motion(m, 30.0);
  ASSERT_FALSE(frames.empty());
  for (const auto& f : frames) {
    EXPECT_FALSE(f.hand(kLeft).valid);
    EXPECT_FALSE(usable(f.hand(kLeft)));
    EXPECT_TRUE(usable(f.hand(kRight)));
    EXPECT_TRUE(usable(f.head()));
  }
  EXPECT_TRUE(tracker_frames_from_motion(Motion(m.skeleton, 120, 0), 30.0).empty());
}

TEST(TrackerMotion, BadRateAndTooManyFramesSayWhy) {
  const Motion m = walk();
  EXPECT_EQ(error_of(m, -1.0, 1000000), "tracker frames: rate must be 0 (the motion's own) or in (0, 10000] Hz, got -1.000000");
  EXPECT_EQ(error_of(m, 20000.0, 1000000), "tracker frames: rate must be 0 (the motion's own) or in (0, 10000] Hz, got 20000.000000");
  EXPECT_NE(error_of(m, std::nan(""), 1000000).find("tracker frames: rate must be 0"), std::string::npos);
  EXPECT_EQ(error_of(m, 0, 10), "tracker frames: " + std::to_string(static_cast<double>(m.frame_count())) +
                                    " frames at 0.000000 Hz exceed the limit of 10");
  EXPECT_EQ(error_of(m, 0, static_cast<std::size_t>(m.frame_count())), "(no error)");  // exactly at the limit is fine
}

}  // namespace
}  // namespace legwork
