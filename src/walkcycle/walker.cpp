#include <legwork/walkcycle/walker.hpp>
#include <legwork/core/fk.hpp>
#include <legwork/core/rotation.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace legwork::walkcycle {

namespace {


// Stairs: the drop is measured for legs this much (a fraction of their
// length) shorter than the soft limit, so the follower's lag does not leave
// them out of reach.
constexpr double kStairsReachMargin = 0.03;

// Index into State::feet: [right heel, right ball, left heel, left ball].
int foot_index(bool left, Pivot p) { return (left ? 2 : 0) + (p == Pivot::Ball ? 1 : 0); }

void feet_of(const CycleModel& m, ConstPoseRef pose, std::array<Vec3, 4>& feet) {
  for (int side = 0; side < 2; ++side) {
    const std::array<Vec3, 2> hb = heel_and_ball(m, pose, side == 1);
    feet[static_cast<std::size_t>(foot_index(side == 1, Pivot::Heel))] = hb[0];
    feet[static_cast<std::size_t>(foot_index(side == 1, Pivot::Ball))] = hb[1];
  }
}

void place(const State& s, PoseRef out) {
  out.rotations[0] = yaw_rotation(s.heading) * out.rotations[0];
  out.translations[0] = yaw_rotation(s.heading) * out.translations[0] + s.offset;
}

// A smooth-root table at cycle time t (periodic, linear between samples).
template <class T>
T table_at(const std::vector<T>& v, const CycleModel& m, double t) {
  const double x = std::fmod(t, m.frames_per_cycle) * Model::samples_per_frame;
  const double xi = std::clamp(std::floor(x), 0.0, static_cast<double>(v.size() - 2));
  const auto i = static_cast<std::size_t>(xi);
  const double u = std::clamp(x - xi, 0.0, 1.0);
  return (1 - u) * v[i] + u * v[i + 1];
}

// The smooth root's floor offset the plan asks for now: its offset less its drag.
Vec3 smooth_target(const Model& model, const State& s) {
  return horizontal(s.offset - yaw_rotation(s.heading) * table_at(model.smooth_root().drag, model.cycle(), s.time));
}

// The walk's first pose: a contact with the root above the start point.
void start_walk(const Model& model, State& s, PoseRef out) {
  const CycleModel& m = model.cycle();
  s.started = true;
  s.time = 0;
  s.decided_step = 0;
  s.heading = s.heading_from = s.heading_to = s.start_heading;
  sample_cycle(m, 0.0, out);
  feet_of(m, out, s.feet);
  s.offset = horizontal(s.start_position - yaw_rotation(s.heading) * horizontal(out.translations[0]));
  if (model.settings().root == RootMotion::Smooth) {  // (the smooth root, not the plan, starts above the start point)
    s.offset += horizontal(yaw_rotation(s.heading) * model.smooth_root().drag.front());
    s.smooth = smooth_target(model, s);
  }
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

// The plan's pose (world, in `pose`; its FK in `before`) moved by `shift`
// with both legs solved so each ankle is where the plan had it (rolled, then
// pulled in by the soft limit if out of reach; lifted if a foot point would
// go below the floor). With `apply` false only measures: returns the pelvis
// drop that would bring every ankle within reach (0 if none is needed) and
// leaves `pose` alone.
double solve_legs(const Model& model, const Ground& ground, PoseRef pose, const Vec3& shift, double heading,
                  const StanceAt& st, const std::array<FootHold, 2>& hold, std::span<Transform> before,
                  std::span<Transform> g, bool apply, Info* info, double reach_margin = 0) {
  const CycleModel& m = model.cycle();
  const Skeleton& sk = m.skeleton;
  leg_kinematics(sk, model.smooth_root().joints, pose, before);
  if (apply) pose.translations[0] += shift;
  shift_legs(model.smooth_root().joints, before, shift, g);
  const LegFrame frame{sk, ground, before, shift, yaw_rotation(heading) * Vec3::UnitZ(), model.settings().soft_reach - reach_margin};
  double drop = 0, roll_max = 0;
  bool limited = false;
  for (int side = 0; side < 2; ++side) {
    const LegIk& leg = model.smooth_root().legs[static_cast<std::size_t>(side)];
    const bool stance = st.left == (side == 1);
    const LegPlacement placed = place_leg(frame, leg, m.foot(side == 1), hold[static_cast<std::size_t>(side)],
                                          stance ? &st.pivot : nullptr, apply, pose, g);
    drop = std::max(drop, placed.drop);
    if (!apply) continue;
    limited = limited || placed.limited;
    roll_max = std::max(roll_max, std::abs(placed.roll));
  }
  if (info) info->foot_roll = roll_max, info->reach_limited = limited;
  return drop;
}

// Each foot's hold this frame: the plan's heel and ball (world) fed to its StanceTurn.
std::array<FootHold, 2> turn_stance_feet(const CycleModel& m, State& s, const StanceAt& st) {
  std::array<FootHold, 2> hold{};
  const double half = m.half_cycle();
  for (int side = 0; side < 2; ++side) {
    StanceTurn::Frame in;
    const Quat yaw = yaw_rotation(s.heading);
    in.heel = yaw * s.feet[static_cast<std::size_t>(foot_index(side == 1, Pivot::Heel))] + s.offset;
    in.ball = yaw * s.feet[static_cast<std::size_t>(foot_index(side == 1, Pivot::Ball))] + s.offset;
    in.stance = st.left == (side == 1);
    in.pivot = st.pivot;
    in.step_fraction = std::clamp((s.time - st.step * half) / half, 0.0, 1.0);
    in.time = s.time, in.step_time = half;
    hold[static_cast<std::size_t>(side)] = s.turn[static_cast<std::size_t>(side)].advance(in);
  }
  return hold;
}

// The pelvis's rise over uneven ground: the mean ground height under the
// plan's heels and balls, followed by two first-order stages of a quarter
// step (y1, y2); 2 y1 - y2 compensates their lag (y2' = (y1 - y2) / tau, a
// ramp's lag is 2 tau times its rate), so a constant grade is followed
// exactly and the rise stays smooth.
double follow_ground(const Model& model, State& s, double frames, double stairs_height) {
  const Ground& ground = model.settings().ground;
  if (ground.flat()) return 0.0;
  double target = 1e300;  // the lowest: the leg reaching down is the one that runs out of reach
  for (const Vec3& p : s.feet) target = std::min(target, ground.height(yaw_rotation(s.heading) * p + s.offset));
  if (ground.stepped()) target = stairs_height;  // (the lower foot's height: plant_feet)
  if (!s.rise_started) {
    s.rise = {target, target};
    s.rise_started = true;
  }
  const double a = 1.0 - std::exp(-frames / (0.25 * model.cycle().half_cycle()));
  s.rise[0] += a * (target - s.rise[0]);
  s.rise[1] += a * (s.rise[0] - s.rise[1]);
  return 2 * s.rise[0] - s.rise[1];
}

// Stairs: the plant of a foot whose heel is (or will be) at `heel` (world)
// facing `heading`, standing flat (fit_on_tread on its heel, ball and toe tip).
State::Plant plant_at(const Ground& ground, const Vec3& heel, double heading, const std::array<double, 2>& reach) {
  const Vec3 u(std::sin(heading), 0.0, std::cos(heading));
  auto along = [&](const Vec3& p) { return (p - ground.origin).dot(ground.direction); };
  const double h = along(heel), ball = along(heel + reach[0] * u), tip = along(heel + reach[1] * u);
  const double toe = std::max(tip, ball + (reach[1] - reach[0]));  // (the toes laid flat ahead of the ball)
  FootExtent e;
  e.lo = std::min({h, ball, toe}), e.hi = std::max({h, ball, toe}), e.ball_lo = e.ball_hi = ball;
  State::Plant p;
  p.move = fit_on_tread(ground, e, p.height);
  return p;
}

// Stairs: where the swing foot (`side`) will land, planted: its heel now (the
// plan's) plus the straight walk's travel to the landing, turned to the
// heading it will have then (the latched one, or the one asked for).
State::Plant predict_plant(const Model& model, const State& s, const StanceAt& st, int side) {
  const Ground& ground = model.settings().ground;
  const Model::SmoothRoot& sr = model.smooth_root();
  double land;  // heading at the landing: half way through the next step's blend
  if (s.decided_step > st.step) {
    land = 0.5 * (s.heading_from + s.heading_to);
  } else {
    const double turn = model.settings().max_turn_per_step;
    land = s.heading_to + 0.5 * std::clamp(wrap_angle(s.desired_heading - s.heading_to), -turn, turn);
  }
  const Vec3 heel = yaw_rotation(s.heading) * s.feet[static_cast<std::size_t>(foot_index(side == 1, Pivot::Heel))] + s.offset;
  const Vec3 landing = horizontal(heel + yaw_rotation(land) * table_at(sr.to_landing, model.cycle(), s.time));
  return plant_at(ground, landing, land, sr.foot_reach[static_cast<std::size_t>(side)]);
}

// Stairs: each foot planted flat on its tread while it bears the weight, and
// carried from one plant to the next while it swings - along the stairs over
// the whole swing, up over its first 60 % (the toes clear the riser ahead)
// or down over its last 60 % (they clear the edge behind), as walk_path's.
// Adds to `hold` (lift, offset); returns the mean height of the two feet.
double plant_feet(const Model& model, State& s, const StanceAt& st, std::array<FootHold, 2>& hold) {
  const Ground& ground = model.settings().ground;
  const Model::SmoothRoot& sr = model.smooth_root();
  const double half = model.cycle().half_cycle();
  for (int side = 0; side < 2; ++side) {
    const auto i = static_cast<std::size_t>(side);
    const bool stance = st.left == (side == 1);
    if (!s.plants_started) {
      const Vec3 heel = yaw_rotation(s.heading) * s.feet[static_cast<std::size_t>(foot_index(side == 1, Pivot::Heel))] + s.offset;
      s.plant_on[i] = s.plant_next[i] = plant_at(ground, horizontal(heel), s.heading, sr.foot_reach[i]);  // (where it stands)
    }
    FootHold& h = hold[i];
    if (stance) {
      if (!s.stance_was[i] && s.plants_started) s.plant_on[i] = s.plant_next[i];  // landed on the plant its swing aimed at
      s.next_fixed[i] = false;
      h.lift = s.plant_on[i].height;
      h.tread = s.plant_on[i].move * ground.direction;
    } else {
      if (!s.next_fixed[i]) s.plant_next[i] = predict_plant(model, s, st, side);
      s.next_fixed[i] = s.decided_step > st.step;  // (the landing's heading is latched: the plant stays)
      const double u = std::clamp((s.time - st.step * half) / half, 0.0, 1.0);
      const State::Plant &p = s.plant_on[i], &q = s.plant_next[i];
      const double w = q.height >= p.height ? smoothstep(u / 0.6) : smoothstep((u - 0.4) / 0.6);
      h.lift = p.height + w * (q.height - p.height);
      h.tread = (p.move + smoothstep(u) * (q.move - p.move)) * ground.direction;
    }
    h.offset += h.tread;
    s.stance_was[i] = stance;
  }
  s.plants_started = true;
  // The pelvis follows the lower foot - the stance foot's tread or the swing
  // foot's way from one tread to the next, eased over the whole step (the
  // foot itself rises or falls over 60 % of it): the leg reaching down is
  // the one that runs out of reach.
  const auto stance_side = static_cast<std::size_t>(st.left ? 1 : 0), swing_side = 1 - stance_side;
  const double u = std::clamp((s.time - st.step * half) / half, 0.0, 1.0);
  const State::Plant &from = s.plant_on[swing_side], &to = s.plant_next[swing_side];
  // (A smooth minimum, no kink where the two cross: within 0.3 m of each
  // other they blend, the minimum itself where they are equal or further
  // apart. Same test, 3 cm: up to 38 m/s^2 of pelvis acceleration against 34.)
  const double a = s.plant_on[stance_side].height, b = from.height + smoothstep(u) * (to.height - from.height), k = 0.3;
  const double d = a - b;
  return b + d * (1.0 - smoothstep((d + k) / (2 * k)));
}

// Stairs: the cycle's rate, easing (over about a step) to Settings::stairs_cadence
// while a foot's plant differs in height from another's, back to 1 on a landing.
void follow_cadence(const Model& model, State& s, double frames) {
  const bool climbing = s.plant_on[0].height != s.plant_on[1].height || s.plant_next[0].height != s.plant_on[0].height ||
                        s.plant_next[1].height != s.plant_on[1].height;
  const double target = climbing ? model.settings().stairs_cadence : 1.0;
  s.rate += (1.0 - std::exp(-frames / model.cycle().half_cycle())) * (target - s.rate);
}

// Smooth root, per frame (`frames` cycle frames advanced): the root follows
// the plan's offset less its drag; the legs reach the plan's ankles.
void smooth_frame(const Model& model, State& s, double frames, const StanceAt& st, PoseRef out, Info* info) {
  const CycleModel& m = model.cycle();
  const Model::SmoothRoot& sr = model.smooth_root();
  const double follow = 0.5 * m.half_cycle();  // cycle frames: half a step
  s.smooth += horizontal(yaw_rotation(s.heading) * sr.velocity * frames);
  s.smooth += (1.0 - std::exp(-frames / follow)) * (smooth_target(model, s) - s.smooth);
  const Ground& ground = model.settings().ground;
  double drop = table_at(sr.drop, m, s.time);
  std::array<FootHold, 2> hold{};
  if (model.settings().turn_on_ball) hold = turn_stance_feet(m, s, st);
  const double stairs_height = ground.stepped() ? plant_feet(model, s, st, hold) : 0.0;
  const double rise = follow_ground(model, s, frames, stairs_height);
  if (info) info->ground_rise = rise;
  if (ground.stepped()) {
    // The drop the legs need to reach the treads (with a margin of 3 % of
    // their length for the follower's lag), followed by two first-order
    // stages of an eighth of a step, their lag compensated (as the rise).
    const double need = std::max(drop, solve_legs(model, ground, out, s.smooth - s.offset + Vec3(0, rise, 0), s.heading, st, hold,
                                                  s.plan_space, s.model_space, false, nullptr, kStairsReachMargin));
    if (!s.drop_started) s.drop_stage = {need, need}, s.drop_started = true;
    const double a = 1.0 - std::exp(-frames / (0.125 * m.half_cycle()));
    s.drop_stage[0] += a * (need - s.drop_stage[0]);
    s.drop_stage[1] += a * (s.drop_stage[0] - s.drop_stage[1]);
    drop = std::max(0.0, 2 * s.drop_stage[0] - s.drop_stage[1]);
    follow_cadence(model, s, frames);
  }
  if (info) info->pelvis_drop = drop;
  solve_legs(model, ground, out, s.smooth - s.offset + Vec3(0, rise - drop, 0), s.heading, st, hold, s.plan_space,
             s.model_space, true, info);
}

// Periodic running maximum over +-`half_width` samples, then a periodic mean over as many.
std::vector<double> spread_drop(const std::vector<double>& need, int half_width) {
  const int n = static_cast<int>(need.size());
  auto at = [&](const std::vector<double>& v, int i) { return v[static_cast<std::size_t>(((i % n) + n) % n)]; };
  std::vector<double> env(need.size()), out(need.size() + 1);
  for (int i = 0; i < n; ++i) {
    double mx = 0;
    for (int k = -half_width; k <= half_width; ++k) mx = std::max(mx, at(need, i + k));
    env[static_cast<std::size_t>(i)] = mx;
  }
  for (int i = 0; i < n; ++i) {
    double sum = 0;
    for (int k = -half_width; k <= half_width; ++k) sum += at(env, i + k);
    out[static_cast<std::size_t>(i)] = sum / (2 * half_width + 1);
  }
  out.back() = out.front();
  return out;
}

// The smooth root's tables (Model::SmoothRoot) from a straight walk of the plan.
Model::SmoothRoot tabulate_smooth_root(const Model& model) {
  const CycleModel& m = model.cycle();
  const int n = m.frames_per_cycle * Model::samples_per_frame;
  Model::SmoothRoot sr;
  Pose pose(m.skeleton);
  std::vector<Transform> before(static_cast<std::size_t>(m.skeleton.joint_count())), g(before.size());
  sample_cycle(m, 0.0, pose.ref());
  forward_kinematics(m.skeleton, pose.ref(), before);
  sr.legs = {leg_of(m.skeleton, false, before), leg_of(m.skeleton, true, before)};
  sr.joints = leg_joints(m);
  const std::vector<Vec3> o = straight_pivot_travel(m, Model::samples_per_frame);
  sr.velocity = o.back() / m.frames_per_cycle;
  sr.drag.resize(o.size());
  Vec3 mean = Vec3::Zero();
  for (int i = 0; i <= n; ++i) {
    sr.drag[static_cast<std::size_t>(i)] = o[static_cast<std::size_t>(i)] - sr.velocity * (static_cast<double>(i) / Model::samples_per_frame);
    if (i < n) mean += sr.drag[static_cast<std::size_t>(i)] / n;
  }
  for (Vec3& d : sr.drag) d -= mean;
  return sr;
}

// The drop the straight walk needs at each sample, spread (needs the legs and drag of `model`).
std::vector<double> tabulate_drop(const Model& model) {
  const CycleModel& m = model.cycle();
  const int n = m.frames_per_cycle * Model::samples_per_frame;
  Pose pose(m.skeleton);
  std::vector<Transform> before(static_cast<std::size_t>(m.skeleton.joint_count())), g(before.size());
  const std::vector<Vec3> o = straight_pivot_travel(m, Model::samples_per_frame);
  std::vector<double> need(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / Model::samples_per_frame;
    sample_cycle(m, t, pose.ref());
    pose.translations[0] += o[static_cast<std::size_t>(i)];
    const Vec3 shift = -model.smooth_root().drag[static_cast<std::size_t>(i)];
    need[static_cast<std::size_t>(i)] = solve_legs(model, Ground{}, pose.ref(), shift, 0.0, stance_at(m, t), {}, before, g, false, nullptr);
  }
  const int quarter = static_cast<int>(std::ceil(m.half_cycle() / 4 * Model::samples_per_frame));
  return spread_drop(need, quarter);
}

// Stairs: the straight walk's travel of the swing foot's heel from each
// sample to its landing, and each foot's ball and toe tip ahead of its heel
// in the standing pose (Model::SmoothRoot::to_landing, foot_reach).
void tabulate_landing(Model::SmoothRoot& sr, const CycleModel& m) {
  const int spf = Model::samples_per_frame, n = m.frames_per_cycle * spf;
  const std::vector<Vec3> o = straight_pivot_travel(m, spf);
  Pose pose(m.skeleton);
  sample_cycle(m, m.half_cycle(), pose.ref());
  const Vec3 right_lands = heel_and_ball(m, pose.ref(), false)[0] + o[static_cast<std::size_t>(n / 2)];
  sample_cycle(m, 0.0, pose.ref());
  const Vec3 left_lands = heel_and_ball(m, pose.ref(), true)[0] + o[static_cast<std::size_t>(n)];
  sr.to_landing.assign(static_cast<std::size_t>(n) + 1, Vec3::Zero());
  for (int i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / spf;
    sample_cycle(m, t, pose.ref());
    const bool swing_left = !stance_at(m, t).left;
    const Vec3 now = heel_and_ball(m, pose.ref(), swing_left)[0] + o[static_cast<std::size_t>(i)];
    sr.to_landing[static_cast<std::size_t>(i)] = horizontal((swing_left ? left_lands : right_lands) - now);
  }
  sr.to_landing.back() = sr.to_landing.front();
  std::vector<Transform> g(static_cast<std::size_t>(m.skeleton.joint_count()));
  forward_kinematics(m.skeleton, m.stand, g);
  for (int side = 0; side < 2; ++side) {
    const FootPivots& f = m.foot(side == 1);
    const Transform& a = g[static_cast<std::size_t>(f.ankle)];
    const Vec3 heel = a.apply(f.heel_local), ball = a.apply(f.ball_local);
    const Vec3 tip = f.toe >= 0 ? end_site_position(m.skeleton, g, f.toe) : ball;
    sr.foot_reach[static_cast<std::size_t>(side)] = {horizontal(ball - heel).norm(), std::max(horizontal(ball - heel).norm(), horizontal(tip - heel).norm())};
  }
}

// The walker's ground: finite, a consistent height field or stairs, and
// only with the smooth root (only the legs can put the feet on it).
void check_ground(const Settings& s) {
  const Ground& g = s.ground;
  if (g.flat()) return;
  if (s.root != RootMotion::Smooth)
    throw Error("walker: ground: uneven ground (" + g.describe() + ") needs the smooth root: the legs' IK puts the feet on it");
  if (!g.origin.allFinite() || !g.direction.allFinite() || !std::isfinite(g.grade) || !std::isfinite(g.length) ||
      !std::isfinite(g.cell))
    throw Error("walker: ground: origin, direction, grade, length and cell must be finite");
  if (g.kind == Ground::Kind::HeightField &&
      (!(g.cell > 0) || g.columns < 1 || g.rows < 1 || g.heights.size() != static_cast<std::size_t>(g.columns) * static_cast<std::size_t>(g.rows)))
    throw Error("walker: ground: a height field needs cell > 0 and rows x columns heights, got " + std::to_string(g.rows) +
                " x " + std::to_string(g.columns) + " and " + std::to_string(g.heights.size()) + " heights");
  for (double h : g.heights)
    if (!std::isfinite(h)) throw Error("walker: ground: a height field's heights must be finite");
  if (g.stepped() && (!std::isfinite(g.rise) || !(g.run >= Ground::kMinRun && g.run <= Ground::kMaxRun) || g.count < 1 ||
                      std::abs(g.direction.norm() - 1.0) > 1e-6))
    throw Error("walker: ground: stairs need a finite rise, a run of 0.2 to 5 m, at least one step and a unit direction");
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
  if (!(settings.soft_reach > 0 && settings.soft_reach <= 1))
    throw Error("walker: soft_reach must be in (0, 1] (a fraction of the leg's length), got " + std::to_string(settings.soft_reach));
  if (!(settings.stairs_cadence > 0 && settings.stairs_cadence <= 1))
    throw Error("walker: stairs_cadence must be in (0, 1] (a fraction of the cycle's rate), got " +
                std::to_string(settings.stairs_cadence));
  check_ground(settings);
  if (settings.root != RootMotion::Smooth && settings.root != RootMotion::Pivot)
    throw Error("walker: root must be RootMotion::Smooth or RootMotion::Pivot, got " + std::to_string(static_cast<int>(settings.root)));
  Model m;
  m.cycle_ = cycle;
  m.settings_ = settings;
  if (settings.root == RootMotion::Smooth) {
    m.cycle_.floor_clamp = false;  // (the legs keep the feet above the floor)
    m.smooth_ = tabulate_smooth_root(m);
    m.smooth_.drop = tabulate_drop(m);
    if (settings.ground.stepped()) tabulate_landing(m.smooth_, m.cycle_);
  }
  return m;
}

State::State(const Model& model)
    : plan_space(static_cast<std::size_t>(model.skeleton().joint_count())), model_space(plan_space.size()) {
  reset(model, *this);
}

void reset(const Model& model, State& s) { reset(model, s, model.settings().start_position, model.settings().start_heading); }

void reset(const Model&, State& s, const Vec3& position, double heading) {
  s.clock.reset();
  s.started = false;
  s.time = 0;
  s.decided_step = 0;
  s.offset = s.smooth = Vec3::Zero();
  s.feet = {};
  s.turn = {};
  s.rise = {};
  s.rise_started = false;
  s.plant_on = s.plant_next = {};
  s.stance_was = s.next_fixed = {};
  s.plants_started = false;
  s.drop_stage = {};
  s.drop_started = false;
  s.rate = 1;
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
  double frames = 0;  // cycle frames advanced
  if (!s.started) {
    start_walk(model, s, out);
    stance = stance_at(m, 0.0);
  } else {
    // A restarted clock keeps walking from here, without advancing.
    const double seconds = step.verdict == FrameClock::Verdict::Restart ? 0.0 : step.dt * s.rate;
    const double was = s.time;
    stance = advance(m, model.settings().max_turn_per_step, s, seconds, out);
    frames = s.time - was;
  }
  if (model.settings().root == RootMotion::Smooth) smooth_frame(model, s, frames, stance, out, info);
  if (info) {
    info->step = stance.step;
    info->cycle_time = s.time;
    info->heading = s.heading;
    info->desired_heading = s.desired_heading;
    info->left_planted = stance.left;
    info->pivot = stance.pivot;
    info->cadence = s.rate;
  }
  if (step.verdict == FrameClock::Verdict::Restart) return UpdateStatus::Restarted;
  return steered ? UpdateStatus::Ok : UpdateStatus::Degraded;
}

void describe(const Info& i, InfoFields& out) {
  out.add("step", i.step);
  out.add("heading", i.heading);
  out.add("desired_heading", i.desired_heading);
  out.add("planted", i.left_planted ? "left" : "right");
  out.add("pivot", i.pivot == Pivot::Heel ? "heel" : "ball");
  out.add("pelvis_drop", i.pelvis_drop);
  out.add("reach_limited", i.reach_limited ? 1.0 : 0.0);
}

}  // namespace legwork::walkcycle
