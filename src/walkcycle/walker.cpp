#include <legwork/walkcycle/walker.hpp>
#include <legwork/core/rotation.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace legwork::walkcycle {

namespace {


// Index into State::feet: [right heel, right ball, left heel, left ball].
int foot_index(bool left, Pivot p) { return (left ? 2 : 0) + (p == Pivot::Ball ? 1 : 0); }

void feet_of(const CycleModel& m, ConstPoseRef pose, std::array<Vec3, 4>& feet) {
  for (int side = 0; side < 2; ++side)
    for (Pivot p : {Pivot::Heel, Pivot::Ball}) feet[static_cast<std::size_t>(foot_index(side == 1, p))] = foot_point(m, pose, side == 1, p);
}

void place(const State& s, PoseRef out) {
  out.rotations[0] = yaw_rotation(s.heading) * out.rotations[0];
  out.translations[0] = yaw_rotation(s.heading) * out.translations[0] + s.offset;
}

// The walk's first pose: a contact with the root above the start point.
void start_walk(const CycleModel& m, State& s, PoseRef out) {
  s.started = true;
  s.time = 0;
  s.decided_step = 0;
  s.heading = s.heading_from = s.heading_to = s.start_heading;
  sample_cycle(m, 0.0, out);
  feet_of(m, out, s.feet);
  s.offset = horizontal(s.start_position - yaw_rotation(s.heading) * horizontal(out.translations[0]));
  place(s, out);
}

// Advances the walk by `seconds`, steering towards s.desired_heading.
StanceAt advance(const CycleModel& m, double max_turn, State& s, double seconds, PoseRef out) {
  const double half = m.half_cycle();
  const double t_prev = s.time;
  const double t = t_prev + std::max(0.0, seconds) * m.fps;
  // Latch the heading of every step whose blend begins by now (mid-step).
  while ((s.decided_step + 0.5) * half <= t) {
    ++s.decided_step;
    s.heading_from = s.heading_to;
    double d = wrap_angle(s.desired_heading - s.heading_from);
    d = std::clamp(d, -max_turn, max_turn);
    s.heading_to = s.heading_from + d;
  }
  const double u = (t - (s.decided_step - 0.5) * half) / half;
  const double heading = s.heading_from + (s.heading_to - s.heading_from) * smoothstep(s.decided_step > 0 ? u : 1.0);
  sample_cycle(m, t, out);
  std::array<Vec3, 4> feet;
  feet_of(m, out, feet);
  const StanceAt st = stance_at(m, 0.5 * (t_prev + t));
  const auto k = static_cast<std::size_t>(foot_index(st.left, st.pivot));
  // Keep the pivot where it was: world = yaw_rotation(heading) * in-place + offset.
  const Vec3 was = yaw_rotation(s.heading) * s.feet[k] + s.offset;
  s.offset = horizontal(was - yaw_rotation(heading) * feet[k]);
  s.heading = heading;
  s.feet = feet;
  s.time = t;
  place(s, out);
  return st;
}

// The heading a usable head asks for (its yaw), if it is not looking straight up or down.
bool head_heading(const DevicePose& head, double& heading) {
  if (!usable(head)) return false;
  const Vec3 f = head.rotation.normalized() * Vec3::UnitZ();
  if (f.x() * f.x() + f.z() * f.z() < 1e-8) return false;
  heading = heading_of(f);
  return true;
}

}  // namespace

Model make_model(const CycleModel& cycle, const Settings& settings) {
  if (cycle.frames_per_cycle < 2 || !(cycle.fps > 0) || !std::isfinite(cycle.fps) || cycle.rotation.empty())
    throw Error("walker: the cycle is not built (" + std::to_string(cycle.frames_per_cycle) + " frames per cycle at " +
                std::to_string(cycle.fps) + " fps, " + std::to_string(cycle.rotation.size()) + " joints)");
  if (!std::isfinite(settings.max_turn_per_step) || settings.max_turn_per_step < 0)
    throw Error("walker: max_turn_per_step must be a finite angle >= 0 (radians), got " +
                std::to_string(settings.max_turn_per_step));
  if (!settings.start_position.allFinite() || !std::isfinite(settings.start_heading))
    throw Error("walker: the start position and heading must be finite");
  Model m;
  m.cycle_ = cycle;
  m.settings_ = settings;
  return m;
}

State::State(const Model& model) { reset(model, *this); }

void reset(const Model& model, State& s) { reset(model, s, model.settings().start_position, model.settings().start_heading); }

void reset(const Model&, State& s, const Vec3& position, double heading) {
  s.clock.reset();
  s.started = false;
  s.time = 0;
  s.decided_step = 0;
  s.offset = Vec3::Zero();
  s.feet = {};
  s.start_position = horizontal(position);
  s.start_heading = s.desired_heading = s.heading = s.heading_from = s.heading_to = heading;
}

UpdateStatus update(const Model& model, const TrackerFrame& frame, State& s, PoseRef out, Info* info) {
  const CycleModel& m = model.cycle();
  if (out.joint_count() != m.skeleton.joint_count()) return UpdateStatus::Rejected;  // a pose of another skeleton
  const FrameClock::Step step = s.clock.advance(frame.time);
  if (step.verdict == FrameClock::Verdict::Reject) return UpdateStatus::Rejected;
  const bool steered = head_heading(frame.head(), s.desired_heading);
  StanceAt stance;
  if (!s.started) {
    start_walk(m, s, out);
    stance = stance_at(m, 0.0);
  } else {
    // A restarted clock keeps walking from here, without advancing.
    const double seconds = step.verdict == FrameClock::Verdict::Restart ? 0.0 : step.dt;
    stance = advance(m, model.settings().max_turn_per_step, s, seconds, out);
  }
  if (info) {
    info->step = stance.step;
    info->cycle_time = s.time;
    info->heading = s.heading;
    info->desired_heading = s.desired_heading;
    info->left_planted = stance.left;
    info->pivot = stance.pivot;
  }
  if (step.verdict == FrameClock::Verdict::Restart) return UpdateStatus::Restarted;
  return steered ? UpdateStatus::Ok : UpdateStatus::Degraded;
}

}  // namespace legwork::walkcycle
