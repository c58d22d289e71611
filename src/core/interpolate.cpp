#include <legwork/core/interpolate.hpp>

#include <algorithm>
#include <cmath>

namespace legwork {

Quat nlerp(const Quat& a, const Quat& b, double t) {
  const double sign = a.dot(b) < 0 ? -1.0 : 1.0;
  Quat q(a.coeffs() * (1 - t) + b.coeffs() * (sign * t));
  q.normalize();
  return q;
}

Quat slerp(const Quat& a, const Quat& b, double t) {
  double d = a.dot(b);
  const double sign = d < 0 ? -1.0 : 1.0;
  d = std::abs(d);
  if (d > 0.9995) return nlerp(a, b, t);  // nearly equal: nlerp is exact enough and stable
  // sin((1 - t) theta) = sin(theta) cos(t theta) - cos(theta) sin(t theta), with
  // cos(theta) = d and sin(theta) = sqrt(1 - d^2) (>= 0.03 here): one acos and
  // one sincos instead of an acos and three sines (per joint and frame in the
  // accentuation's blends, where the four were 5 % of its time).
  const double theta = std::acos(d);
  const double s = std::sqrt(1.0 - d * d);
  const double st = std::sin(t * theta), ct = std::cos(t * theta);
  const double wa = ct - d * st / s;
  const double wb = sign * st / s;
  Quat q(a.coeffs() * wa + b.coeffs() * wb);
  q.normalize();
  return q;
}

void blend_poses(ConstPoseRef a, ConstPoseRef b, double t, PoseRef out) {
  const auto n = a.rotations.size();
  for (std::size_t j = 0; j < n; ++j) {
    out.rotations[j] = slerp(a.rotations[j], b.rotations[j], t);
    out.translations[j] = a.translations[j] * (1 - t) + b.translations[j] * t;
  }
}

void sample_motion(const Motion& m, double t, PoseRef out) {
  const int last = m.frame_count() - 1;
  const double x = std::clamp(t * m.fps, 0.0, static_cast<double>(std::max(last, 0)));
  const int i0 = std::min(static_cast<int>(std::floor(x)), last);
  const int i1 = std::min(i0 + 1, last);
  blend_poses(m.frame(i0), m.frame(i1), x - i0, out);
}

int resampled_frame_count(const Motion& m, double fps) {
  if (!(fps > 0) || !std::isfinite(fps)) throw Error("resample: frame rate must be positive, got " + std::to_string(fps));
  if (m.frame_count() == 0) return 0;
  // In double first: a huge rate must not overflow the int it becomes.
  const double frames = std::floor(m.duration() * fps + 1e-6) + 1;
  if (!(frames * std::max(m.joint_count(), 1) <= kMaxResampledJointPoses))
    throw Error("resample: " + std::to_string(m.duration()) + " s at " + std::to_string(fps) + " Hz is " +
                std::to_string(static_cast<long long>(std::min(frames, 1e18))) + " frames x " +
                std::to_string(m.joint_count()) + " joints, more than " +
                std::to_string(static_cast<long long>(kMaxResampledJointPoses)) + " joint poses");
  return static_cast<int>(frames);
}

Motion resample(const Motion& m, double fps) {
  const int frames = resampled_frame_count(m, fps);
  Motion out(m.skeleton, fps, frames);
  for (int f = 0; f < frames; ++f) sample_motion(m, f / fps, out.frame(f));
  return out;
}

Motion trim(const Motion& m, int first, int last) {
  if (first < 0 || last >= m.frame_count() || first > last)
    throw Error("trim: frames " + std::to_string(first) + ":" + std::to_string(last) +
                " are outside 0:" + std::to_string(m.frame_count() - 1));
  Motion out(m.skeleton, m.fps, last - first + 1);
  for (int f = first; f <= last; ++f) out.set_frame(f - first, m.frame(f));
  return out;
}

Motion concatenate(const Motion& a, const Motion& b) {
  if (a.skeleton.names != b.skeleton.names) throw Error("concatenate: the motions have different skeletons");
  if (std::abs(a.fps - b.fps) > 1e-9) throw Error("concatenate: frame rates differ; resample first");
  Motion out = a;
  for (int f = 0; f < b.frame_count(); ++f) out.push_back(b.frame(f));
  return out;
}

}  // namespace legwork
