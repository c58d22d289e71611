// One avatar, two sources, on real CMU walks: the upper body from head and
// hands (IK avatar, or accentuation over a database), the legs from
// walking-in-place on the ankles; legs fade between the sources without
// popping; the per-frame contract (bad time, no allocation).
#include <legwork/combined/combined.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>

#include "accent/accent_testing.hpp"
// alloc_counter.hpp replaces new/delete with malloc/free; GCC 12 sees the
// replaced operator delete inlined next to std::allocator and warns of a mismatch
// that is not one (both sides are the counter's malloc/free).
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#include "alloc_counter.hpp"
#include "cmu_sample.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace legwork;

namespace {

constexpr double kRate = 30.0;

combined::Settings settings_at_rate() {
  combined::Settings s;
  s.wip.signal.rate = kRate;
  return s;
}

std::vector<TrackerFrame> walk_frames(const char* trial = "cmu/bvh/walking/07_01.bvh") {
  return tracker_frames_from_motion(testdata::load_sample(trial), kRate);
}

double angle(const Quat& a, const Quat& b) { return a.angularDistance(b); }

}  // namespace

TEST(Combined, LegsComeFromWalkingInPlaceAndTheRestFromTheUpperMethod) {
  const Skeleton& skel = testdata::sample_skeleton();
  const auto frames = walk_frames();
  combined::Settings settings = settings_at_rate();
  settings.foot_lock = false;  // walking-in-place's legs exactly
  const combined::Model model = combined::make_model(skel, settings);
  combined::State state(model);
  // The two sources alone, on the same frames.
  ik::State ik_state(*model.ik());
  wip::State wip_state(model.wip());
  Pose pose(model.skeleton()), ik_pose(model.skeleton()), wip_pose(model.skeleton());
  const int knee = skel.roles[Role::LeftKnee], chest = skel.roles[Role::Chest] >= 0 ? skel.roles[Role::Chest] : skel.roles[Role::Neck];
  int walking = 0, full_weight = 0;
  for (const auto& f : frames) {
    combined::Info info;
    ASSERT_NE(combined::update(model, f, state, pose.ref(), &info), UpdateStatus::Rejected);
    ik::update(*model.ik(), f, ik_state, ik_pose.ref());
    wip::update(model.wip(), f, wip_state, wip_pose.ref());
    walking += info.walking;
    EXPECT_LT(angle(pose.rotations[static_cast<std::size_t>(chest)], ik_pose.rotations[static_cast<std::size_t>(chest)]), 1e-9);
    if (info.legs_weight == 1.0) {
      ++full_weight;
      EXPECT_LT(angle(pose.rotations[static_cast<std::size_t>(knee)], wip_pose.rotations[static_cast<std::size_t>(knee)]), 1e-9);
    }
  }
  EXPECT_GT(walking, static_cast<int>(frames.size()) / 3) << "the real walk's ankles drive walking-in-place";
  EXPECT_GE(full_weight, static_cast<int>(frames.size()) - static_cast<int>(std::ceil(0.3 * kRate)) - 1)
      << "the legs reach walking-in-place within blend_time";
  EXPECT_EQ(model.leg_joints().size(), 8u);  // CMU: LeftUpLeg (the hip role), LeftLeg, LeftFoot, LeftToeBase; and right
}

TEST(Combined, ALockedFootStaysWhereItTouchedDown) {
  const Skeleton& skel = testdata::sample_skeleton();
  const auto frames = walk_frames("cmu/bvh/walking/16_15.bvh");
  const combined::Model model = combined::make_model(skel, settings_at_rate());
  combined::State state(model);
  Pose pose(model.skeleton());
  std::vector<Transform> g(static_cast<std::size_t>(skel.joint_count()));
  const int ankles[2] = {skel.roles[Role::LeftAnkle], skel.roles[Role::RightAnkle]};
  std::array<Vec3, 2> held{Vec3::Zero(), Vec3::Zero()};
  std::array<bool, 2> was{false, false};
  double worst = 0, travel = 0;
  int locked_frames = 0;
  Vec3 root0 = Vec3::Zero();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    combined::Info info;
    combined::update(model, frames[i], state, pose.ref(), &info);
    forward_kinematics(skel, pose, g);
    if (i == 0) root0 = pose.translations[0];
    travel = (pose.translations[0] - root0).norm();
    for (int f = 0; f < 2; ++f) {
      const Vec3 a = g[static_cast<std::size_t>(ankles[f])].translation;
      if (info.foot_locked[f] && was[f] && info.legs_weight == 1.0) {
        worst = std::max(worst, (a - held[f]).norm());
        ++locked_frames;
      }
      held[f] = a;
      was[f] = info.foot_locked[f];
    }
  }
  std::printf("[combined] 16_15: %d locked foot-frames, root travelled %.2f m, a held ankle moved at most %.2f mm per frame\n",
              locked_frames, travel, worst * 1e3);
  EXPECT_GT(travel, 1.0);
  EXPECT_GT(locked_frames, static_cast<int>(frames.size()) / 2);
  EXPECT_LT(worst, 0.005) << "a held ankle moves only when re-planted (leg out of reach)";
}

TEST(Combined, LosingTheFeetFadesTheLegsInsteadOfPopping) {
  const Skeleton& skel = testdata::sample_skeleton();
  auto frames = walk_frames();
  const std::size_t lost = frames.size() / 2;
  for (std::size_t i = lost; i < frames.size(); ++i) frames[i].foot(kLeft).valid = frames[i].foot(kRight).valid = false;
  const combined::Model model = combined::make_model(skel, settings_at_rate());
  combined::State state(model);
  Pose pose(model.skeleton()), prev(model.skeleton());
  const int knee = skel.roles[Role::RightKnee];
  // Frame-to-frame knee rotation around the moment the feet are lost, with
  // the fade, and what a hard switch would do at that moment. The IK legs
  // the fade goes to step on their own (up to ~30 degrees a frame), so the
  // fade's step is measured beyond the IK legs' own step that frame.
  ik::State ik_state(*model.ik());
  Pose ik_pose(model.skeleton()), ik_prev(model.skeleton());
  double fade_max_step = 0, hard_jump = 0, last_weight = 1;
  int fade_frames = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    combined::Info info;
    prev = pose;
    combined::update(model, frames[i], state, pose.ref(), &info);
    ik_prev = ik_pose;
    ik::update(*model.ik(), frames[i], ik_state, ik_pose.ref());
    if (i < lost) continue;
    EXPECT_FALSE(info.feet_tracked);
    EXPECT_LE(info.legs_weight, last_weight);
    EXPECT_NEAR(last_weight - info.legs_weight, info.legs_weight > 0 ? 1.0 / (0.3 * kRate) : last_weight - info.legs_weight, 1e-9);
    if (i == lost) hard_jump = angle(prev.rotations[static_cast<std::size_t>(knee)], ik_pose.rotations[static_cast<std::size_t>(knee)]);
    if (last_weight > 0) {
      ++fade_frames;
      const auto k = static_cast<std::size_t>(knee);
      const double ik_step = angle(ik_prev.rotations[k], ik_pose.rotations[k]);
      fade_max_step = std::max(fade_max_step, angle(prev.rotations[k], pose.rotations[k]) - ik_step);
    }
    last_weight = info.legs_weight;
  }
  EXPECT_EQ(last_weight, 0.0);
  EXPECT_EQ(fade_frames, static_cast<int>(std::ceil(0.3 * kRate)));
  std::printf("[combined] feet lost at frame %zu: hard switch would jump the knee %.1f deg; fading, the largest step beyond the IK legs' own is %.1f deg\n",
              lost, rad2deg(hard_jump), rad2deg(fade_max_step));
  EXPECT_LT(fade_max_step, hard_jump);
}

TEST(Combined, BadTimeLeavesStateAndPoseAlone) {
  const combined::Model model = combined::make_model(testdata::sample_skeleton(), settings_at_rate());
  combined::State state(model);
  const auto frames = walk_frames();
  Pose pose(model.skeleton());
  for (int i = 0; i < 40; ++i) combined::update(model, frames[static_cast<std::size_t>(i)], state, pose.ref());
  const Pose before = pose;
  const double weight = state.legs_weight;
  for (double t : {std::numeric_limits<double>::quiet_NaN(), frames[39].time, frames[10].time, -1.0}) {
    TrackerFrame f = frames[40];
    f.time = t;
    EXPECT_EQ(combined::update(model, f, state, pose.ref()), UpdateStatus::Rejected) << t;
  }
  EXPECT_EQ(state.legs_weight, weight);
  for (std::size_t j = 0; j < pose.rotations.size(); ++j) EXPECT_EQ(pose.rotations[j].coeffs(), before.rotations[j].coeffs());
  EXPECT_NE(combined::update(model, frames[40], state, pose.ref()), UpdateStatus::Rejected);
  Pose wrong(testdata::sample_skeleton());
  wrong.rotations.pop_back();
  wrong.translations.pop_back();
  EXPECT_EQ(combined::update(model, frames[41], state, wrong.ref()), UpdateStatus::Rejected);
}

TEST(Combined, UpdatesAllocateNothingWithEitherUpperBody) {
  const accent::Database db = accent::testing::indexed_database({"walking/07_01", "walking/16_15"});
  combined::Settings s = settings_at_rate();
  s.accent.user_height = 1.75;
  const combined::Model with_db = combined::make_model(db, s);
  const combined::Model with_ik = combined::make_model(testdata::sample_skeleton(), s);
  const auto frames = walk_frames("cmu/bvh/walking/07_02.bvh");
  for (const combined::Model* m : {&with_db, &with_ik}) {
    combined::State state(*m);
    Pose pose(m->skeleton());
    combined::Info info;
    const long n = alloc_count::count_allocations([&] {
      for (const auto& f : frames) combined::update(*m, f, state, pose.ref(), &info);
    });
    EXPECT_EQ(n, 0) << (m->accentuated() ? "accent" : "ik") << " upper body";
    EXPECT_TRUE(info.walking || info.distance > 0);
  }
}

TEST(Combined, ModelErrorsNameTheProblem) {
  combined::Settings s;
  s.blend_time = 0;
  try {
    (void)combined::make_model(testdata::sample_skeleton(), s);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "combined: blend_time 0.000000 s must be positive");
  }
}
