#pragma once
// Small rotation and vector helpers used by every module (one definition each).
// Angles in radians; yaw is about +y with 0 facing +z (legwork's convention).
// Header-only, no allocation, no exceptions.
#include <legwork/core/skeleton.hpp>

#include <algorithm>
#include <cmath>

namespace legwork {

inline bool all_finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }
inline bool all_finite(const Quat& q) {
  return std::isfinite(q.w()) && std::isfinite(q.x()) && std::isfinite(q.y()) && std::isfinite(q.z());
}

// Rotation about +y by `yaw` radians.
inline Quat yaw_rotation(double yaw) { return Quat(Eigen::AngleAxisd(yaw, Vec3::UnitY())); }
// Heading of a direction about y (0 = facing +z), or `fallback` if it is (nearly) vertical.
inline double heading_of(const Vec3& dir, double fallback = 0.0) {
  if (dir.x() * dir.x() + dir.z() * dir.z() < 1e-8) return fallback;
  return std::atan2(dir.x(), dir.z());
}
// Yaw of a rotation: the heading its +z axis points to.
inline double yaw_of(const Quat& q) {
  const Vec3 f = q * Vec3::UnitZ();
  return std::atan2(f.x(), f.z());
}
// The same, or `fallback` when the rotation looks (almost) straight up or down
// and has no usable yaw.
inline double yaw_of(const Quat& q, double fallback) {
  const Vec3 f = q * Vec3::UnitZ();
  return std::hypot(f.x(), f.z()) > 1e-3 ? std::atan2(f.x(), f.z()) : fallback;
}
// Wraps an angle to [-pi, pi].
inline double wrap_angle(double a) { return std::remainder(a, 2.0 * kPi); }
// The horizontal (x, z) part of a vector.
inline Vec3 horizontal(const Vec3& v) { return {v.x(), 0.0, v.z()}; }
// 3u^2 - 2u^3 of u clamped to [0, 1].
inline double smoothstep(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

// Rotation vector (axis * angle) of a unit quaternion, shortest arc, and back.
// Small rotations (the per-frame steps of the filters: under 11.4 degrees)
// take truncated series instead of atan2 / sin / cos; at their bounds the
// first omitted term is below 1e-17 of the result, so they agree with the
// library's functions to rounding.
inline Vec3 rotation_log(Quat q) {
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Vec3 v(q.x(), q.y(), q.z());
  const double s2 = v.squaredNorm(), w = q.w();
  if (s2 < 1e-24) return 2.0 * v;
  if (s2 < 0.01 * w * w) {  // x = |v| / w < 0.1: 2 atan(x) / |v| = (2 / w) atan(x) / x
    const double x2 = s2 / (w * w);
    double p = 1.0 / 17;
    for (const double c : {-1.0 / 15, 1.0 / 13, -1.0 / 11, 1.0 / 9, -1.0 / 7, 1.0 / 5, -1.0 / 3, 1.0}) p = p * x2 + c;
    return v * (2.0 / w * p);
  }
  const double s = std::sqrt(s2);
  return v * (2.0 * std::atan2(s, w) / s);
}
inline Quat rotation_exp(const Vec3& r) {
  const double a2 = r.squaredNorm();
  if (a2 < 1e-24) return Quat(1.0, 0.5 * r.x(), 0.5 * r.y(), 0.5 * r.z()).normalized();
  if (a2 < 0.04) {  // half angle h < 0.1: cos h and sin(h) / h as polynomials in h^2
    const double h2 = 0.25 * a2;
    double c = -1.0 / 3628800, sh = -1.0 / 39916800;
    for (const double k : {1.0 / 40320, -1.0 / 720, 1.0 / 24, -0.5, 1.0}) c = c * h2 + k;
    for (const double k : {1.0 / 362880, -1.0 / 5040, 1.0 / 120, -1.0 / 6, 1.0}) sh = sh * h2 + k;
    const double f = 0.5 * sh;  // the vector part: (r / |r|) sin h = r (sin(h) / h) / 2
    return Quat(c, f * r.x(), f * r.y(), f * r.z());
  }
  const double angle = std::sqrt(a2);
  return Quat(Eigen::AngleAxisd(angle, r / angle));
}

// Direction of joint j's bone in its rest frame: toward the mean of its
// children's offsets, else its end site, else `fallback`.
inline Vec3 rest_direction(const Skeleton& s, int j, const Vec3& fallback = Vec3::UnitY()) {
  Vec3 d = Vec3::Zero();
  for (int c = j + 1; c < s.joint_count(); ++c)
    if (s.parents[static_cast<std::size_t>(c)] == j) d += s.rest_offsets[static_cast<std::size_t>(c)];
  if (d.norm() < 1e-9 && s.has_end_site[static_cast<std::size_t>(j)]) d = s.end_sites[static_cast<std::size_t>(j)];
  return d.norm() < 1e-9 ? fallback : Vec3(d.normalized());
}

}  // namespace legwork
