// Rotation vectors (include/legwork/core/rotation.hpp): rotation_log and
// rotation_exp against the library's atan2 / sin / cos, on the per-frame
// steps of real motion and across the small-angle series' bounds.
#include <legwork/core/rotation.hpp>

#include "core_samples.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace legwork;

namespace {
// The closed forms, through the library's functions.
Vec3 log_by_atan2(Quat q) {
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Vec3 v(q.x(), q.y(), q.z());
  const double s = v.norm();
  return s < 1e-12 ? Vec3(2.0 * v) : Vec3(v * (2.0 * std::atan2(s, q.w()) / s));
}
Quat exp_by_sincos(const Vec3& r) {
  const double a = r.norm();
  return a < 1e-12 ? Quat(1.0, 0.5 * r.x(), 0.5 * r.y(), 0.5 * r.z()).normalized() : Quat(Eigen::AngleAxisd(a, r / a));
}
double coeff_diff(const Quat& a, const Quat& b) { return (a.coeffs() - b.coeffs()).cwiseAbs().maxCoeff(); }

// A unit rotation of `angle` radians about a random axis.
Quat turn(std::mt19937& rng, double angle) {
  std::normal_distribution<double> n;
  const Vec3 axis = Vec3(n(rng), n(rng), n(rng)).normalized();
  return Quat(Eigen::AngleAxisd(angle, axis));
}
}  // namespace

TEST(Rotation, LogAndExpAgreeWithTheLibraryAcrossTheSeriesBounds) {
  std::mt19937 rng(7);
  // Both sides of the series' bounds (tan(angle / 2) = 0.1 for the log, a
  // 0.2 rad rotation vector for the exp), tiny and large angles, 3,000 axes.
  const double bound_log = 2.0 * std::atan(0.1), bound_exp = 0.2;
  for (const double angle : {1e-9, 1e-6, 1e-3, 0.05, bound_exp * (1 - 1e-9), bound_log * (1 - 1e-9), bound_log * (1 + 1e-9),
                             bound_exp * (1 + 1e-9), 0.5, 2.0, 3.1}) {
    double worst_log = 0, worst_exp = 0;
    for (int k = 0; k < 3000; ++k) {
      const Quat q = turn(rng, angle);
      const Vec3 r = log_by_atan2(q);
      worst_log = std::max(worst_log, (rotation_log(q) - r).norm() / std::max(angle, 1e-300));
      worst_exp = std::max(worst_exp, coeff_diff(rotation_exp(r), exp_by_sincos(r)));
      // The shortest arc: -q gives the same rotation vector.
      EXPECT_LT((rotation_log(Quat(-q.coeffs())) - r).norm(), 1e-15 * std::max(angle, 1.0)) << angle;
    }
    // A few units in the last place: the same numbers as atan2 / sin / cos.
    EXPECT_LT(worst_log, 2e-15) << "angle " << angle;
    EXPECT_LT(worst_exp, 2e-16) << "angle " << angle;
  }
}

TEST(Rotation, PerFrameStepsOfARealWalkRoundTrip) {
  // The steps the filters take: each joint's rotation from one frame of the
  // sample walk to the next (120 Hz), on both sides of the series' bounds.
  const Motion m = testdata::walk();
  int steps = 0, beyond = 0;  // joints x frame pairs; those past the series' bounds
  double worst = 0, largest = 0;
  for (int f = 1; f < m.frame_count(); ++f)
    for (int j = 0; j < m.skeleton.joint_count(); ++j) {
      const Quat a = m.frame(f - 1).rotations[static_cast<std::size_t>(j)], b = m.frame(f).rotations[static_cast<std::size_t>(j)];
      const Quat step = (b * a.conjugate()).normalized();
      const Vec3 r = rotation_log(step);
      largest = std::max(largest, r.norm());
      beyond += r.norm() > 0.2;
      worst = std::max(worst, (r - log_by_atan2(step)).norm());
      worst = std::max(worst, coeff_diff(rotation_exp(r), exp_by_sincos(r)));
      // exp(log(q)) is q up to sign.
      EXPECT_LT(testdata::quat_distance(rotation_exp(r), step), 1e-15);
      ++steps;
    }
  EXPECT_GT(largest, 0.01);       // real motion, not only near-identities
  EXPECT_GT(beyond, 0);           // both paths taken
  EXPECT_LT(beyond, steps / 10);  // mostly the series'
  EXPECT_LT(worst, 1e-15);
}
