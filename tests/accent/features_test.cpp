// Feature extraction and rotation alignment against analytic answers.
#include <legwork/accent/offline/builder.hpp>
#include <legwork/accent/features.hpp>
#include <legwork/core/rotation.hpp>

#include "accent_testing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace legwork::accent {
namespace {

TEST(AccentFeatures, QuadraticTrajectoryGivesAnalyticVelocityAndAcceleration) {
  // p(t) = p0 + v0 t + a t^2 / 2: backward differences give the exact velocity
  // at the midpoint of each step and the exact (constant) acceleration. The
  // window's samples are kStride database samples apart.
  const double fps = 90.0, dt = kStride / fps;
  const Vec3 p0(0.3, -0.4, 0.2), v0(1.2, -0.5, 0.7), a(-3.0, 2.0, 9.0);
  auto p = [&](double t) -> Vec3 { return p0 + v0 * t + 0.5 * a * t * t; };
  HandWindow w;
  for (int i = 0; i < kWindow; ++i) w[static_cast<std::size_t>(i)] = p(i * dt);
  RawFeature f;
  raw_feature(w, fps, f);
  for (int i = 0; i < kWindow; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[static_cast<std::size_t>(3 * i + c)], p(i * dt)[c], 1e-12);
  for (int i = 1; i < kWindow; ++i) {
    const Vec3 v_mid = v0 + a * ((i - 0.5) * dt);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[static_cast<std::size_t>(kPosDim + 3 * (i - 1) + c)], v_mid[c], 1e-9);
  }
  for (int i = 2; i < kWindow; ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(f[static_cast<std::size_t>(kPosDim + 3 * (kWindow - 1) + 3 * (i - 2) + c)], a[c], 1e-6);
}

TEST(AccentFeatures, SinusoidDerivativesMatchAnalyticWithinDiscretisationError) {
  const double fps = 90.0, omega = 2 * kPi * 1.5, r = 0.3;  // a 1.5 Hz circle, 30 cm radius
  HandWindow w;
  for (int i = 0; i < kWindow; ++i) {
    const double t = i * kStride / fps;
    w[static_cast<std::size_t>(i)] = Vec3(r * std::cos(omega * t), 0.1, r * std::sin(omega * t));
  }
  RawFeature f;
  raw_feature(w, fps, f);
  // Speed is r * omega everywhere; centripetal acceleration r * omega^2.
  for (int i = 1; i < kWindow; ++i) {
    const auto o = static_cast<std::size_t>(kPosDim + 3 * (i - 1));
    EXPECT_NEAR(Vec3(f[o], f[o + 1], f[o + 2]).norm(), r * omega, r * omega * 2e-3);
  }
  for (int i = 2; i < kWindow; ++i) {
    const auto o = static_cast<std::size_t>(kPosDim + 3 * (kWindow - 1) + 3 * (i - 2));
    EXPECT_NEAR(Vec3(f[o], f[o + 1], f[o + 2]).norm(), r * omega * omega, r * omega * omega * 5e-3);
  }
}

// Window s turned about y by `angle`: x' = c x + s z, z' = -s x + c z.
AlignXZ rotated_about_y(const AlignXZ& s, double angle) {
  AlignXZ q;
  const double c = std::cos(angle), sn = std::sin(angle);
  for (int k = 0; k < 2 * kWindow; ++k) {
    const double x = s[static_cast<std::size_t>(2 * k)], z = s[static_cast<std::size_t>(2 * k + 1)];
    q[static_cast<std::size_t>(2 * k)] = static_cast<float>(c * x + sn * z);
    q[static_cast<std::size_t>(2 * k + 1)] = static_cast<float>(-sn * x + c * z);
  }
  return q;
}

TEST(AccentAlignment, RecoversAKnownRotationAboutY) {
  // A real database window (07_01's hands), rotated about y by known angles.
  const auto trials = testing::sample_trials({"walking/07_01"});
  BuildConfig cfg;
  cfg.speed_variants = 0;
  const Database db = build_database(trials, cfg);
  ASSERT_GT(db.window_count(), 50);
  for (double angle : {0.0, 0.3, -1.1, 2.5, -3.0}) {
    for (int win : {10, db.window_count() / 2}) {
      const AlignXZ& s = db.align(win);
      const AlignQuery q = align_query(rotated_about_y(s, angle));
      // Float storage of q bounds the achievable precision; compare in double on the same data.
      EXPECT_NEAR(std::remainder(align_yaw(q, s) - angle, 2 * kPi), 0.0, 1e-6) << "angle " << angle << " window " << win;
      // The engine's per-candidate form: the same turn as a quaternion, without the angle.
      const Quat turn = align_turn(q, s), expected = yaw_rotation(align_yaw(q, s));
      EXPECT_NEAR(std::abs(turn.dot(expected)), 1.0, 1e-12) << "angle " << angle << " window " << win;
      EXPECT_NEAR(turn.norm(), 1.0, 1e-12);
      EXPECT_GE(turn.w(), 0.0);
      EXPECT_NEAR(turn.x(), 0.0, 0.0);
      EXPECT_NEAR(turn.z(), 0.0, 0.0);
    }
  }
  // Small angles keep their precision (the half-angle sine from the sine, not from 1 - cos).
  const AlignXZ& s = db.align(10);
  for (double angle : {1e-3, -2e-5, 1e-7}) {
    const AlignQuery q = align_query(rotated_about_y(s, angle));
    const double yaw = align_yaw(q, s);
    EXPECT_NEAR(align_turn(q, s).y(), std::sin(yaw / 2), 1e-15) << "angle " << angle;
  }
}

TEST(AccentFeatures, ProjectedDistanceEqualsScaledRawDistance) {
  const auto trials = testing::sample_trials({"walking/07_01"});
  const Database db = build_database(trials, BuildConfig{});
  const FeatureSpace& fs = db.feature_space();
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 0.2);
  for (int trial = 0; trial < 20; ++trial) {
    HandWindow a, b;
    for (int i = 0; i < kWindow; ++i) {
      a[static_cast<std::size_t>(i)] = Vec3(n(rng), n(rng) - 0.5, n(rng));
      b[static_cast<std::size_t>(i)] = a[static_cast<std::size_t>(i)] + Vec3(n(rng), n(rng), n(rng)) * 0.1;
    }
    Feature fa, fb;
    fs.project(a, fa);
    fs.project(b, fb);
    double d2 = 0;
    for (int d = 0; d < kDim; ++d) d2 += std::pow(double(fa[static_cast<std::size_t>(d)]) - fb[static_cast<std::size_t>(d)], 2);
    const double raw = fs.raw_distance(a, b);
    EXPECT_NEAR(std::sqrt(d2), raw, 1e-4 * raw + 1e-3);
  }
}

}  // namespace
}  // namespace legwork::accent
