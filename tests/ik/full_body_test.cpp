// Full-body IK avatar (ik::update) driven by real CMU head and hand tracks;
// the per-frame contract: time rules, bad device samples, no allocation.
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/ik/full_body.hpp>
#include <legwork/io/bvh.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>

#include "pose_checks.hpp"
#include "alloc_counter.hpp"
#include "cmu_sample.hpp"
#include "testdata.hpp"

namespace legwork::ik {
namespace {

using testdata::finite_pose;
using testdata::same_pose;

Motion load90(const std::string& rel) { return resample(testdata::load_sample(rel), 90.0); }

// The tracker frame of a motion frame: head and wrists as the devices.
TrackerFrame tracker_of(const Skeleton& s, std::span<const Transform> g, double time) {
  TrackerFrame t;
  t.time = time;
  const auto at = [&](Role r) { return g[static_cast<std::size_t>(s.roles[r])]; };
  t.head() = {at(Role::Head).translation, at(Role::Head).rotation, true};
  t.hand(kLeft) = {at(Role::LeftHand).translation, at(Role::LeftHand).rotation, true};
  t.hand(kRight) = {at(Role::RightHand).translation, at(Role::RightHand).rotation, true};
  return t;
}

std::vector<TrackerFrame> trackers_of(const Motion& m) {
  std::vector<TrackerFrame> out;
  std::vector<Transform> g(static_cast<std::size_t>(m.skeleton.joint_count()));
  for (int f = 0; f < m.frame_count(); ++f) {
    forward_kinematics(m.skeleton, m.frame(f), g);
    out.push_back(tracker_of(m.skeleton, g, f / m.fps));
  }
  return out;
}

// One avatar on the sample walk at 90 Hz, with its tracker frames.
struct WalkAvatar {
  Motion walk = load90("cmu/bvh/walking/07_01.bvh");
  Model model = make_model(walk.skeleton);
  State state{model};
  Pose pose{walk.skeleton};
  std::vector<TrackerFrame> frames = trackers_of(walk);
};

struct IkRun {
  Motion out;
  double head_err = 0, hand_err = 0, max_hand_err = 0, max_head_err = 0;
  double lower_err = 0, full_err = 0;
  int steps = 0;
};

IkRun drive(const Motion& truth) {
  const Skeleton& skel = truth.skeleton;
  const Model model = make_model(skel);
  State state(model);
  IkRun r{Motion(skel, truth.fps, truth.frame_count()), 0, 0, 0, 0, 0, 0, 0};
  std::vector<Transform> g(static_cast<std::size_t>(skel.joint_count())), o(g.size());
  int lower_n = 0;
  for (int f = 0; f < truth.frame_count(); ++f) {
    forward_kinematics(skel, truth.frame(f), g);
    const TrackerFrame in = tracker_of(skel, g, f / truth.fps);
    EXPECT_EQ(update(model, in, state, r.out.frame(f)), UpdateStatus::Ok);
    forward_kinematics(skel, r.out.frame(f), o);
    const auto pos = [&](std::span<const Transform> x, Role role) { return x[static_cast<std::size_t>(skel.roles[role])].translation; };
    const double he = (pos(o, Role::Head) - in.head().position).norm();
    const double le = (pos(o, Role::LeftHand) - in.hand(kLeft).position).norm();
    const double re = (pos(o, Role::RightHand) - in.hand(kRight).position).norm();
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

// Controllers 3 cm further out than the real hands (along shoulder -> hand).
// Where the arm cannot reach, the clavicle swings; the arm's IK must then start
// from the moved shoulder, so each hand ends on its controller whenever the
// controller is within the arm's length of the output's shoulder, and short of
// it by exactly the rest otherwise (the two-bone solve straightens the arm).
TEST(FullBodyIk, HandsBeyondTheArmsReachSwingTheClaviclesAndReachFromTheMovedShoulder) {
  WalkAvatar a;
  const Motion& truth = a.walk;
  const Skeleton& skel = truth.skeleton;
  std::vector<Transform> g(static_cast<std::size_t>(skel.joint_count())), o(g.size());
  const auto at = [&](std::span<const Transform> x, Role r) { return x[static_cast<std::size_t>(skel.roles[r])].translation; };
  const Role clavicles[2] = {Role::LeftClavicle, Role::RightClavicle}, shoulders[2] = {Role::LeftShoulder, Role::RightShoulder},
             elbows[2] = {Role::LeftElbow, Role::RightElbow}, hands[2] = {Role::LeftHand, Role::RightHand};
  int swung = 0, short_of_reach = 0;
  double worst_excess_error = 0;
  for (int f = 0; f < truth.frame_count(); ++f) {
    forward_kinematics(skel, truth.frame(f), g);
    TrackerFrame in = a.frames[static_cast<std::size_t>(f)];
    for (int s = 0; s < 2; ++s) in.hand(s).position += 0.03 * (at(g, hands[s]) - at(g, shoulders[s])).normalized();
    ASSERT_NE(update(a.model, in, a.state, a.pose.ref()), UpdateStatus::Rejected);
    forward_kinematics(skel, a.pose.ref(), o);
    for (int s = 0; s < 2; ++s) {
      swung += a.pose.rotations[static_cast<std::size_t>(skel.roles[clavicles[s]])].angularDistance(Quat::Identity()) > 1e-6;
      const double arm = (at(o, elbows[s]) - at(o, shoulders[s])).norm() + (at(o, hands[s]) - at(o, elbows[s])).norm();
      const double beyond = std::max(0.0, (in.hand(s).position - at(o, shoulders[s])).norm() - arm);
      short_of_reach += beyond > 0;
      const double miss = (at(o, hands[s]) - in.hand(s).position).norm();
      worst_excess_error = std::max(worst_excess_error, std::abs(miss - beyond));
    }
  }
  std::printf("07_01, controllers 3 cm out: a clavicle swung on %d of %d arm-frames, %d still beyond reach; "
              "hand miss - distance beyond reach: worst %.2g m\n",
              swung, 2 * truth.frame_count(), short_of_reach, worst_excess_error);
  EXPECT_GT(swung, truth.frame_count() / 10);
  EXPECT_LT(worst_excess_error, 1e-6);
}

TEST(FullBodyIk, StandingStillPlantsTheFeetAndCrouchesWhenTheHeadDrops) {
  const Motion walk = load90("cmu/bvh/walking/07_01.bvh");
  const Skeleton& skel = walk.skeleton;
  const Model model = make_model(skel);
  State state(model);
  Pose pose(skel);
  std::vector<Transform> g(static_cast<std::size_t>(skel.joint_count()));
  TrackerFrame in;
  const double h0 = model.standing_head_height();
  in.head() = {Vec3(0.3, h0, 1.0), Quat::Identity(), true};
  in.hand(kLeft) = {Vec3(0.55, h0 - 0.55, 1.05), Quat::Identity(), true};
  in.hand(kRight) = {Vec3(0.05, h0 - 0.55, 1.05), Quat::Identity(), true};
  Vec3 ankle_start = Vec3::Zero();
  double pelvis_standing = 0;
  for (int f = 0; f < 180; ++f) {
    // Two seconds standing, then the head sinks 40 cm over two seconds.
    const double drop = f < 90 ? 0.0 : 0.4 * (f - 90) / 89.0;
    TrackerFrame x = in;
    x.time = f / 90.0;
    for (Device d : {Device::Head, Device::LeftHand, Device::RightHand}) x[d].position.y() -= drop;
    Info info;
    EXPECT_EQ(update(model, x, state, pose.ref(), &info), UpdateStatus::Ok);
    EXPECT_FALSE(info.stepping[0] || info.stepping[1]) << "frame " << f;
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

TEST(FullBodyIk, BadDeviceSamplesNeverReachThePose) {
  WalkAvatar a;
  const Skeleton& skel = a.walk.skeleton;
  const Model& model = a.model;
  State& state = a.state;
  Pose& pose = a.pose;
  const std::vector<TrackerFrame>& frames = a.frames;
  std::vector<Transform> g(static_cast<std::size_t>(skel.joint_count()));
  EXPECT_EQ(update(model, frames[10], state, pose.ref()), UpdateStatus::Ok);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // A lost, NaN or 1e30 head: the last usable head is held (Degraded), never NaN.
  for (int variant = 0; variant < 4; ++variant) {
    TrackerFrame bad = frames[11 + variant];
    switch (variant) {
      case 0: bad.head().position.x() = nan; break;
      case 1: bad.head().position = Vec3(1e30, 0, 0); break;
      case 2: bad.head().rotation.coeffs() = Eigen::Vector4d(0, 0, 0, 0); break;
      default: bad.head().valid = false; break;
    }
    Info info;
    EXPECT_EQ(update(model, bad, state, pose.ref(), &info), UpdateStatus::Degraded) << variant;
    EXPECT_FALSE(info.head_tracked);
    ASSERT_TRUE(finite_pose(pose)) << variant;
    forward_kinematics(skel, pose, g);
    EXPECT_LT((g[static_cast<std::size_t>(skel.roles[Role::Head])].translation - frames[10].head().position).norm(), 1e-6)
        << "variant " << variant << ": the head is held where it was last seen";
  }
  // A lost right controller (NaN, 1e30, invalid): that arm relaxes.
  for (int variant = 0; variant < 3; ++variant) {
    TrackerFrame bad = frames[20 + variant];
    if (variant == 0) bad.hand(kRight).position = Vec3::Constant(nan);
    if (variant == 1) bad.hand(kRight).position = Vec3(0, -1e30, 0);
    if (variant == 2) bad.hand(kRight).valid = false;
    Info info;
    EXPECT_EQ(update(model, bad, state, pose.ref(), &info), UpdateStatus::Degraded);
    EXPECT_TRUE(info.head_tracked && info.hand_tracked[kLeft] && !info.hand_tracked[kRight]);
    forward_kinematics(skel, pose, g);
    for (const auto& t : g) ASSERT_TRUE(t.translation.allFinite() && t.rotation.coeffs().allFinite());
    // The right wrist hangs below its shoulder.
    EXPECT_LT(g[static_cast<std::size_t>(skel.roles[Role::RightHand])].translation.y(),
              g[static_cast<std::size_t>(skel.roles[Role::RightShoulder])].translation.y() - 0.3);
  }
  // Good data again: the head is exact at once.
  EXPECT_EQ(update(model, frames[30], state, pose.ref()), UpdateStatus::Ok);
  forward_kinematics(skel, pose, g);
  EXPECT_LT((g[static_cast<std::size_t>(skel.roles[Role::Head])].translation - frames[30].head().position).norm(), 1e-6);
}

TEST(FullBodyIk, NoHeadYetStandsAtTheOriginThenStartsWhereTheHeadIs) {
  WalkAvatar a;
  const Model& model = a.model;
  State& state = a.state;
  Pose& pose = a.pose;
  const std::vector<TrackerFrame>& frames = a.frames;
  for (int f = 0; f < 5; ++f) {
    TrackerFrame x = frames[static_cast<std::size_t>(f)];
    x.head().valid = false;
    EXPECT_EQ(update(model, x, state, pose.ref()), UpdateStatus::Degraded);
    EXPECT_TRUE(finite_pose(pose));
  }
  Info info;
  for (int f = 5; f < 10; ++f) EXPECT_EQ(update(model, frames[static_cast<std::size_t>(f)], state, pose.ref(), &info), UpdateStatus::Ok);
  EXPECT_EQ(info.steps_taken, 0);  // the feet started under the real head, not at the origin
  EXPECT_FALSE(info.stepping[0] || info.stepping[1]);
}

TEST(FullBodyIk, TimeRules) {
  WalkAvatar a;
  const Model& model = a.model;
  State& state = a.state;
  Pose& pose = a.pose;
  const std::vector<TrackerFrame>& frames = a.frames;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // A NaN first time: rejected, the stream starts at the next good frame.
  TrackerFrame x = frames[0];
  x.time = nan;
  EXPECT_EQ(update(model, x, state, pose.ref()), UpdateStatus::Rejected);
  for (std::size_t f = 0; f < 100; ++f) ASSERT_EQ(update(model, frames[f], state, pose.ref()), UpdateStatus::Ok) << f;
  // Backward, repeated, infinite and absurd times leave pose and state untouched.
  const Pose before = pose;
  const State::Foot foot = state.feet[0];
  for (double t : {frames[50].time, frames[99].time, std::numeric_limits<double>::infinity(), nan, 1e30}) {
    x = frames[100];
    x.time = t;
    EXPECT_EQ(update(model, x, state, pose.ref()), UpdateStatus::Rejected) << t;
    EXPECT_TRUE(same_pose(pose, before)) << t;
    EXPECT_EQ(state.feet[0].position, foot.position);
  }
  // A far-future spike: a gap, so the avatar restarts there; when the real
  // clock comes back it restarts after FrameClock::kRestartFrames frames and
  // then runs normally.
  x = frames[100];
  x.time = 1e6;
  EXPECT_EQ(update(model, x, state, pose.ref()), UpdateStatus::Restarted);
  std::size_t f = 101;
  UpdateStatus st = UpdateStatus::Rejected;
  int rejected = 0;
  for (; st == UpdateStatus::Rejected && f < 130; ++f) {
    st = update(model, frames[f], state, pose.ref());
    rejected += st == UpdateStatus::Rejected;
  }
  EXPECT_EQ(st, UpdateStatus::Restarted);
  EXPECT_EQ(rejected, FrameClock::kRestartFrames - 1);
  Info info;
  ASSERT_GT(frames.size(), f + 90);
  for (; f < frames.size(); ++f) ASSERT_EQ(update(model, frames[f], state, pose.ref(), &info), UpdateStatus::Ok) << f;
  EXPECT_TRUE(finite_pose(pose));
  EXPECT_GT(info.steps_taken, 0);  // walking again
}

TEST(FullBodyIk, AllocatesNothingPerFrame) {
  WalkAvatar a;
  const Model& model = a.model;
  State& state = a.state;
  Pose& pose = a.pose;
  const std::vector<TrackerFrame>& frames = a.frames;
  Info info;
  const long n = alloc_count::count_allocations([&] {
    for (const TrackerFrame& x : frames) update(model, x, state, pose.ref(), &info);
  });
  EXPECT_EQ(n, 0);
  EXPECT_GT(info.steps_taken, 6);  // it did walk
}

TEST(FullBodyIk, TheModelOwnsItsSkeleton) {
  const Motion walk = load90("cmu/bvh/walking/07_01.bvh");
  const std::vector<TrackerFrame> frames = trackers_of(walk);
  std::optional<Skeleton> skel = walk.skeleton;
  const Model model = make_model(*skel);
  skel.reset();  // the caller's skeleton is gone
  State a(model), b(model);
  Pose pa(model.skeleton()), pb(model.skeleton());
  for (std::size_t f = 0; f < 50; ++f) {
    update(model, frames[f], a, pa.ref());
    update(model, frames[f], b, pb.ref());
  }
  EXPECT_TRUE(same_pose(pa, pb));  // two avatars on one model: the same answer
  EXPECT_EQ(model.skeleton().joint_count(), walk.skeleton.joint_count());
}

TEST(FullBodyIk, RejectsASkeletonWithoutArms) {
  Skeleton s;
  s.add_joint("Hips", -1, Vec3::Zero());
  s.add_joint("Head", 0, Vec3(0, 0.6, 0));
  resolve_roles(s);
  try {
    make_model(s);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("full-body IK: the skeleton has no joint for role(s)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace legwork::ik
