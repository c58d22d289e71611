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
inline Vec3 rotation_log(Quat q) {
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Vec3 v(q.x(), q.y(), q.z());
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;
  return v * (2.0 * std::atan2(s, q.w()) / s);
}
inline Quat rotation_exp(const Vec3& r) {
  const double angle = r.norm();
  if (angle < 1e-12) return Quat(1.0, 0.5 * r.x(), 0.5 * r.y(), 0.5 * r.z()).normalized();
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
