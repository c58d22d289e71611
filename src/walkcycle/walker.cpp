#include <legwork/walkcycle/walker.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::walkcycle {

namespace {

Quat yaw(double theta) { return Quat(Eigen::AngleAxisd(theta, Vec3::UnitY())); }
Vec3 horizontal(const Vec3& v) { return Vec3(v.x(), 0.0, v.z()); }
double smoothstep(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * (3 - 2 * u);
}

// Index into WalkerState::feet: [right heel, right ball, left heel, left ball].
int foot_index(bool left, Pivot p) { return (left ? 2 : 0) + (p == Pivot::Ball ? 1 : 0); }

void feet_of(const CycleModel& m, ConstPoseRef pose, std::array<Vec3, 4>& feet) {
  for (int side = 0; side < 2; ++side)
    for (Pivot p : {Pivot::Heel, Pivot::Ball}) feet[static_cast<std::size_t>(foot_index(side == 1, p))] = foot_point(m, pose, side == 1, p);
}

void place(const WalkerState& s, PoseRef out) {
  out.rotations[0] = yaw(s.heading) * out.rotations[0];
  out.translations[0] = yaw(s.heading) * out.translations[0] + s.offset;
}

}  // namespace

void walker_reset(const CycleModel& m, WalkerState& s, const Vec3& position, double heading, PoseRef out) {
  const double max_turn = s.max_turn_per_step;
  s = WalkerState{};
  s.max_turn_per_step = max_turn;
  s.heading = s.heading_from = s.heading_to = heading;
  if (out.rotations.empty()) return;
  sample_cycle(m, 0.0, out);
  feet_of(m, out, s.feet);
  s.offset = horizontal(position - yaw(heading) * horizontal(out.translations[0]));
  place(s, out);
}

void walker_update(const CycleModel& m, WalkerState& s, double seconds, double desired_heading, PoseRef out) {
  const double half = m.half_cycle();
  const double t_prev = s.time;
  const double t = t_prev + std::max(0.0, seconds) * m.fps;
  // Latch the heading of every step whose blend begins by now (mid-step).
  while ((s.decided_step + 0.5) * half <= t) {
    ++s.decided_step;
    s.heading_from = s.heading_to;
    double d = std::remainder(desired_heading - s.heading_from, 2 * kPi);
    d = std::clamp(d, -s.max_turn_per_step, s.max_turn_per_step);
    s.heading_to = s.heading_from + d;
  }
  const double u = (t - (s.decided_step - 0.5) * half) / half;
  const double heading = s.heading_from + (s.heading_to - s.heading_from) * smoothstep(s.decided_step > 0 ? u : 1.0);
  sample_cycle(m, t, out);
  std::array<Vec3, 4> feet;
  feet_of(m, out, feet);
  const StanceAt st = stance_at(m, 0.5 * (t_prev + t));
  const auto k = static_cast<std::size_t>(foot_index(st.left, st.pivot));
  // Keep the pivot where it was: world = yaw(heading) * in-place + offset.
  const Vec3 was = yaw(s.heading) * s.feet[k] + s.offset;
  s.offset = horizontal(was - yaw(heading) * feet[k]);
  s.heading = heading;
  s.feet = feet;
  s.time = t;
  place(s, out);
}

}  // namespace legwork::walkcycle
