// Equations 1-8, avatar scaling, continuity, IK in the loop, allocation-free
// updates, speed, bad input, and behaviour on real CMU walking.
#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/wip/offline/run.hpp>
#include <legwork/wip/offline/synthetic.hpp>
#include <legwork/wip/wip.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"
#include "sample_walk_run.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>


namespace legwork::wip {
namespace {

using samples::cmu_model;

TEST(Equations, TakeTheRestoredValuesAtZeroAndMaximumHeight) {
  const StepShape k{0.6, 0.3};
  const double S = k.S, H = k.H;
  EXPECT_NEAR(first_step_swing(k, 0, true), 0, 1e-12);
  EXPECT_NEAR(first_step_swing(k, H, true), 0.25 * S, 1e-12);
  EXPECT_NEAR(first_step_swing(k, H, false), 0.25 * S, 1e-12);
  EXPECT_NEAR(first_step_swing(k, 0, false), 0.5 * S, 1e-12);
  EXPECT_NEAR(first_step_support(k, 0, true), 0, 1e-12);
  EXPECT_NEAR(first_step_support(k, H, true), -0.25 * S, 1e-12);
  EXPECT_NEAR(first_step_support(k, 0, false), -0.5 * S, 1e-12);
  EXPECT_NEAR(next_step_swing(k, 0, true), -0.5 * S, 1e-12);
  EXPECT_NEAR(next_step_swing(k, H, true), 0, 1e-12);
  EXPECT_NEAR(next_step_swing(k, H, false), 0, 1e-12);
  EXPECT_NEAR(next_step_swing(k, 0, false), 0.5 * S, 1e-12);
  EXPECT_NEAR(next_step_swing(k, H / 2, false), 0.5 * S * std::cos(kPi / 4) + 0.25 * S, 1e-12);  // overshoot term
  EXPECT_NEAR(next_step_support(k, 0, true), 0.5 * S, 1e-12);
  EXPECT_NEAR(next_step_support(k, H, true), 0, 1e-12);
  EXPECT_NEAR(next_step_support(k, 0, false), -0.5 * S, 1e-12);
  // Heights above H are clamped (real marching lifts 0.39 m).
  EXPECT_NEAR(next_step_swing(k, 0.5, true), next_step_swing(k, H, true), 1e-12);
  EXPECT_NEAR(body_drop(0.8, 0.0), 0.0, 1e-12);
  EXPECT_NEAR(body_drop(0.8, -0.3), 0.8 - std::sqrt(0.64 - 0.09), 1e-12);
}

TEST(Mapping, StepLengthAndHintScaleWithTheMeasuredLeg) {
  Skeleton big = cmu_model().skeleton();
  big.scale(1.25);
  const Model m = make_model(big);
  EXPECT_NEAR(m.leg_length(), 1.25 * cmu_model().leg_length(), 1e-9);
  EXPECT_NEAR(m.shape().S / cmu_model().shape().S, 1.25, 1e-9);
  EXPECT_GT(cmu_model().leg_length(), 0.7);
  EXPECT_LT(cmu_model().leg_length(), 0.95);
}

TEST(Mapping, SkeletonWithoutLegsIsRefusedClearly) {
  Skeleton s;
  s.add_joint("Hips", -1, Vec3::Zero());
  s.add_joint("Spine", 0, Vec3(0, 0.2, 0));
  resolve_roles(s);
  try {
    make_model(s);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(std::string(role_name(Role::LeftKnee))), std::string::npos) << e.what();
  }
}

TEST(Mapping, CurvesAreContinuousAndFeetFollowTheTargets) {
  SyntheticOptions o;
  o.noise = 0;
  o.drop_rate = o.nan_rate = 0;
  const auto track = synthetic_stepping(o);
  const Model& m = cmu_model();
  State ws(m);
  Pose pose(m.skeleton());
  const auto cal = calibrate_floor(track.frames);
  ASSERT_TRUE(cal.ok);
  set_floor(ws, cal.floor[0], cal.floor[1]);
  const double dt = 1.0 / 30;
  const double alpha = 1 - std::exp(-dt / m.settings().mapping.smoothing_tau);
  double prev[2] = {0, 0}, max_step = 0, max_target_jump = 0, prev_target[2] = {0, 0};
  int swings = 0, frames = 0, out_of_reach = 0;
  std::vector<Vec3> fk(static_cast<std::size_t>(m.skeleton().joint_count()));
  Info f;
  for (const auto& s : track.frames) {
    ASSERT_NE(update(m, s, ws, pose.ref(), &f), UpdateStatus::Rejected);
    for (int foot = 0; foot < 2; ++foot) {
      max_step = std::max(max_step, std::abs(f.z[foot] - prev[foot]));
      // At foot-off and mid-swing, where the equations switch branch, the
      // targets do not jump (the gaps are faded in). Elsewhere the equations
      // themselves move fast when the foot does (checked by max_step below).
      const unsigned changes = kEventFootOff | kEventMidSwing;
      if ((f.events[0] | f.events[1]) & changes)
        max_target_jump = std::max(max_target_jump, std::abs(f.z_target[foot] - prev_target[foot]));
      prev[foot] = f.z[foot];
      prev_target[foot] = f.z_target[foot];
      swings += (f.events[foot] & kEventFootOff) ? 1 : 0;
    }
    // The solved legs put the ankles on the IK targets.
    forward_positions(m.skeleton(), pose, fk);
    for (int foot = 0; foot < 2; ++foot) {
      const auto& leg = m.leg(foot).chain;
      const Vec3 hip = fk[static_cast<std::size_t>(leg.root)];
      const double reach = (fk[static_cast<std::size_t>(leg.mid)] - hip).norm() +
                           (fk[static_cast<std::size_t>(leg.end)] - fk[static_cast<std::size_t>(leg.mid)]).norm();
      const Vec3 ankle = fk[static_cast<std::size_t>(leg.end)];
      ++frames;
      if ((f.target_world[foot] - hip).norm() < reach - 1e-6) {
        ASSERT_LT((ankle - f.target_world[foot]).norm(), 1e-5) << s.time;
      } else {  // out of reach (the strike overshoot): a straight leg toward the target
        ++out_of_reach;
        ASSERT_GT((ankle - hip).normalized().dot((f.target_world[foot] - hip).normalized()), 1 - 1e-9);
      }
    }
    // Supporting feet stay on the floor.
    for (int foot = 0; foot < 2; ++foot)
      if (!in_swing(f.phase[foot])) {
        ASSERT_NEAR(f.target_world[foot].y(), m.leg(foot).ankle_height, 1e-9);
      }
  }
  EXPECT_EQ(swings, static_cast<int>(track.swings.size()));
  EXPECT_LT(out_of_reach, frames / 20) << out_of_reach << " of " << frames << " leg targets out of reach";
  EXPECT_LE(max_step, alpha * 1.2 * m.shape().S);
  EXPECT_LT(max_target_jump, 1e-9);
}

TEST(Speed, ComfortableSteppingGivesAboutWalkingSpeedAndTheCapHolds) {
  const Model& m = cmu_model();
  auto mean_speed = [&](const SyntheticOptions& o, const Model& model) {
    const auto run = run_wip(model, synthetic_stepping(o).frames, {true, 3.0, false});
    double sum = 0;
    int n = 0;
    for (const auto& f : run.frames)
      if (f.time > 5 && f.time < 10) sum += f.speed, ++n;
    return sum / n;
  };
  SyntheticOptions comfortable;
  EXPECT_NEAR(mean_speed(comfortable, m), 1.3, 0.2);
  SyntheticOptions frantic;
  frantic.step_height = 0.35;
  frantic.cadence = 4.0;
  frantic.pause_length = 0;
  const double fast = mean_speed(frantic, m);
  EXPECT_LE(fast, 3.5 + 1e-9);
  EXPECT_GT(fast, 2.0);
  Settings p;
  p.mapping.speed_model = SpeedModel::StepFrequency;
  SyntheticOptions two_per_second;
  two_per_second.cadence = 2.0;
  EXPECT_NEAR(mean_speed(two_per_second, make_model(m.skeleton(), p)), 1.3, 0.15);
}

}  // namespace
}  // namespace legwork::wip
