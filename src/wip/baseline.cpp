#include <legwork/wip/baseline.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::wip {

std::vector<double> ankle_depths(const Motion& m, int foot) {
  const auto& r = m.skeleton.roles;
  const int ja = r[foot == kLeft ? Role::LeftAnkle : Role::RightAnkle];
  std::vector<double> z(static_cast<std::size_t>(m.frame_count()));
  std::vector<Vec3> pos(static_cast<std::size_t>(m.joint_count()));
  for (int f = 0; f < m.frame_count(); ++f) {
    forward_positions(m.skeleton, m.frame(f), pos);
    z[static_cast<std::size_t>(f)] = pos[static_cast<std::size_t>(ja)].z() - pos[0].z();
  }
  return z;
}

KeyframeBaselineModel make_keyframe_baseline(const Motion& cycle, double avatar_leg) {
  if (cycle.frame_count() < 2) throw Error("key-frame baseline: the walk cycle has fewer than 2 frames");
  KeyframeBaselineModel m;
  m.clip = cycle;
  const double clip_leg = measure_body(cycle.skeleton).leg_length;
  const double k = clip_leg > 0 ? avatar_leg / clip_leg : 1.0;
  for (int f = 0; f < 2; ++f) {
    m.depth[f] = ankle_depths(cycle, f);
    for (double& z : m.depth[f]) z *= k;
  }
  // Idle: the cycle's first frame's upper body over neutral legs is not
  // available without IK; the rest pose at the clip's mean root height stands.
  m.idle = Pose(cycle.skeleton);
  double y = 0;
  for (int f = 0; f < cycle.frame_count(); ++f) y += cycle.frame(f).translations[0].y();
  m.idle.translations[0] = Vec3(0, y / cycle.frame_count(), 0);
  return m;
}

KeyframeBaselineState make_baseline_state(const KeyframeBaselineModel& m) {
  KeyframeBaselineState s;
  s.pose = m.idle;
  return s;
}

void update_baseline(const KeyframeBaselineModel& m, bool walking, double dt, KeyframeBaselineState& s) {
  const double a = 1 - std::exp(-dt / std::max(m.blend_tau, 1e-6));
  s.weight += ((walking ? 1.0 : 0.0) - s.weight) * a;
  const double period = m.clip.frame_count() / m.clip.fps;  // looping: the last frame joins the first
  if (s.weight > 1e-3) s.clip_time = std::fmod(s.clip_time + dt, period);
  else s.clip_time = 0;  // restart the cycle on the next walk
  // Sample the clip (wrapping between the last and first frame).
  const double x = s.clip_time * m.clip.fps;
  const int f0 = static_cast<int>(std::floor(x)) % m.clip.frame_count();
  const int f1 = (f0 + 1) % m.clip.frame_count();
  const double u = x - std::floor(x);
  blend_poses(m.clip.frame(f0), m.clip.frame(f1), u, s.pose.ref());
  blend_poses(m.idle, s.pose, s.weight, s.pose.ref());
  for (int f = 0; f < 2; ++f) {
    const auto& d = m.depth[f];
    const double z = (1 - u) * d[static_cast<std::size_t>(f0)] + u * d[static_cast<std::size_t>(f1)];
    s.z[f] = s.weight * z;
  }
}

}  // namespace legwork::wip
