// Metrics on synthetic cases with known answers, and on a real CMU trial.
#include <legwork/eval/metrics.hpp>
#include <legwork/io/bvh.hpp>

#include <gtest/gtest.h>

#include <cmath>

#include "cmu_sample.hpp"
#include "testdata.hpp"

namespace legwork::eval {
namespace {

std::array<bool, kRoleCount> all_roles() {
  std::array<bool, kRoleCount> p{};
  p.fill(true);
  return p;
}
std::array<bool, kRoleCount> only(std::initializer_list<Role> roles) {
  std::array<bool, kRoleCount> p{};
  for (Role r : roles) p[static_cast<std::size_t>(r)] = true;
  return p;
}

// A moving body: every role joint at a distinct place, hands swinging on
// independent sinusoids, the whole body walking forward.
RoleTrack moving_body(int frames, double fps) {
  RoleTrack t = make_track(fps, frames, all_roles());
  for (int f = 0; f < frames; ++f) {
    const double s = f / fps;
    for (int r = 0; r < kRoleCount; ++r) t.at(f, static_cast<Role>(r)) = Vec3(0.05 * r, 0.08 * r, 0.5 * s);
    t.at(f, Role::LeftHand) += Vec3(0.2 * std::sin(3 * s), 0.1 * std::cos(2 * s), 0.3 * std::sin(s));
    t.at(f, Role::RightHand) += Vec3(0.1 * std::cos(5 * s), 0.2 * std::sin(4 * s), 0.2 * std::cos(1.5 * s));
  }
  return t;
}

TEST(EvalMetrics, EveryRoleIsUpperOrLowerBodyAndInFullBody) {
  for (int r = 0; r < kRoleCount; ++r) {
    const auto role = static_cast<Role>(r);
    EXPECT_NE(role_in_part(role, Part::UpperBody), role_in_part(role, Part::LowerBody)) << role_name(role);
    EXPECT_TRUE(role_in_part(role, Part::FullBody));
  }
  EXPECT_TRUE(role_in_part(Role::Pelvis, Part::LowerBody));
  EXPECT_TRUE(role_in_part(Role::LeftClavicle, Part::UpperBody));
  EXPECT_TRUE(role_in_part(Role::LeftHand, Part::LeftHand));
  EXPECT_FALSE(role_in_part(Role::RightHand, Part::LeftHand));
}

TEST(EvalMetrics, PoseOffsetByKnownVectorGivesItsLengthEverywhere) {
  const RoleTrack truth = moving_body(200, 90);
  RoleTrack out = truth;
  for (auto& p : out.positions) p += Vec3(0.03, 0.0, 0.04);  // 5 cm
  const TrialMetrics m = evaluate_trial(out, truth);
  for (int p = 0; p < kPartCount; ++p) EXPECT_NEAR(m.part_cm[static_cast<std::size_t>(p)], 5.0, 1e-9);
  EXPECT_NEAR(m.mpjpe_cm, 5.0, 1e-9);
  EXPECT_NEAR(m.mpjve_cm_s, 0.0, 1e-9);  // a constant offset moves at the same speed
  // A rigid offset does not change the hand trajectories' shape.
  for (int s = 0; s < 2; ++s) EXPECT_NEAR(m.hand_correlation[static_cast<std::size_t>(s)], 1.0, 1e-9);
  EXPECT_NEAR(m.jitter, m.jitter_truth, 1e-9);
}

TEST(EvalMetrics, OnlyTheOffsetPartCarriesError) {
  const RoleTrack truth = moving_body(100, 90);
  RoleTrack out = truth;
  for (int f = 0; f < out.frames; ++f) out.at(f, Role::LeftKnee) += Vec3(0, 0.1, 0);  // 10 cm
  const TrialMetrics m = evaluate_trial(out, truth);
  EXPECT_NEAR(m.part_cm[static_cast<std::size_t>(Part::UpperBody)], 0.0, 1e-12);
  EXPECT_NEAR(m.part_cm[static_cast<std::size_t>(Part::LeftHand)], 0.0, 1e-12);
  EXPECT_NEAR(m.part_cm[static_cast<std::size_t>(Part::LowerBody)], 10.0 / 9.0, 1e-9);  // 9 lower-body roles
  EXPECT_NEAR(m.mpjpe_cm, 10.0 / kRoleCount, 1e-9);
}

TEST(EvalMetrics, VelocityErrorOfAConstantDrift) {
  // Truth static, output drifting at 0.5 m/s along x: MPJVE = 50 cm/s exactly
  // (central differences are exact on a line).
  RoleTrack truth = make_track(90, 50, only({Role::Head, Role::LeftHand}));
  RoleTrack out = truth;
  for (int f = 0; f < out.frames; ++f) {
    out.at(f, Role::Head).x() = 0.5 * f / 90.0;
    out.at(f, Role::LeftHand).x() = 0.5 * f / 90.0;
  }
  const TrialMetrics m = evaluate_trial(out, truth);
  EXPECT_NEAR(m.mpjve_cm_s, 50.0, 1e-9);
  EXPECT_NEAR(m.jitter, 0.0, 1e-9);
}

TEST(EvalMetrics, KnownJerk) {
  // x = t^3 has jerk 6 m/s^3 everywhere; a cubic's third difference is exact.
  // Two joints present, one static: mean jerk = 3 m/s^3 = 0.03 x 10^2 m/s^3.
  RoleTrack t = make_track(60, 120, only({Role::Pelvis, Role::LeftAnkle}));
  for (int f = 0; f < t.frames; ++f) {
    const double s = f / 60.0;
    t.at(f, Role::LeftAnkle) = Vec3(s * s * s, 0, 0);
  }
  EXPECT_NEAR(mean_jerk(t), 3.0, 1e-6);
  const TrialMetrics m = evaluate_trial(t, t);
  EXPECT_NEAR(m.jitter, 0.03, 1e-8);
}

TEST(EvalMetrics, StaticOutputHandsCorrelateWithNothing) {
  const RoleTrack truth = moving_body(300, 90);
  RoleTrack out = truth;
  for (int f = 0; f < out.frames; ++f) {
    out.at(f, Role::LeftHand) = out.at(f, Role::Head);  // frozen relative to the head
    out.at(f, Role::RightHand) = out.at(f, Role::Head);
  }
  const TrialMetrics m = evaluate_trial(out, truth);
  // Output hands relative to the input head do not move: undefined, left out.
  EXPECT_TRUE(std::isnan(m.hand_correlation[0]));
  EXPECT_TRUE(std::isnan(m.hand_correlation[1]));
}

TEST(EvalMetrics, FootSkatingOfASlidingPlantedFoot) {
  // Left ankle on the floor sliding 1 cm per frame for the first half, then
  // lifted 20 cm and moving fast: only the planted half counts.
  RoleTrack t = make_track(90, 100, only({Role::Head, Role::LeftAnkle}));
  for (int f = 0; f < t.frames; ++f) {
    const bool planted = f < 50;
    t.at(f, Role::LeftAnkle) = Vec3(0.01 * f, planted ? 0.08 : 0.28, planted ? 0.0 : 0.1 * f);
  }
  const FootSkate s = foot_skating(t, 0.03);
  EXPECT_NEAR(s.slide_m, 0.01, 1e-12);
  EXPECT_NEAR(s.contact_fraction, 0.5, 1e-12);
}

TEST(EvalMetrics, CombineIsFrameWeighted) {
  TrialMetrics a, b;
  a.frames = 100;
  b.frames = 300;
  a.part_cm.fill(4.0);
  b.part_cm.fill(8.0);
  a.hand_correlation = {1.0, std::nan("")};
  b.hand_correlation = {0.5, 0.9};
  const std::vector<TrialMetrics> v{a, b};
  const TrialMetrics c = combine(v);
  EXPECT_EQ(c.frames, 400);
  EXPECT_NEAR(c.mpjpe_cm, 7.0, 1e-12);
  EXPECT_NEAR(c.hand_correlation[0], 0.625, 1e-12);
  EXPECT_NEAR(c.hand_correlation[1], 0.9, 1e-12);
}

TEST(EvalMetrics, RealTrialAgainstItselfIsPerfect) {
  const Motion m = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  const RoleTrack t = role_track(m);
  ASSERT_EQ(t.frames, m.frame_count());
  EXPECT_TRUE(t.has(Role::LeftHand) && t.has(Role::RightAnkle) && t.has(Role::Head));
  const TrialMetrics s = evaluate_trial(t, t);
  EXPECT_NEAR(s.mpjpe_cm, 0.0, 1e-12);
  EXPECT_NEAR(s.hand_correlation[0], 1.0, 1e-12);
  EXPECT_NEAR(s.hand_correlation[1], 1.0, 1e-12);
  // A walking capture: feet are planted a good part of the time and slide little.
  EXPECT_GT(s.foot_contact_fraction, 0.2);
  EXPECT_LT(s.foot_skating_truth_cm, 1.0);
  EXPECT_GT(s.jitter_truth, 0.0);
}

TEST(EvalMetrics, MismatchedTracksAreRejected) {
  const RoleTrack a = moving_body(10, 90), b = moving_body(11, 90);
  EXPECT_THROW(evaluate_trial(a, b), Error);
  const RoleTrack c = make_track(90, 10, only({Role::Head})), d = make_track(90, 10, only({Role::LeftHand}));
  EXPECT_THROW(evaluate_trial(c, d), Error);
}

}  // namespace
}  // namespace legwork::eval
