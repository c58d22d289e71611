// Walking-in-place runtime: signal -> gait machines -> equations -> IK.
#include <legwork/wip/wip.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/measure.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::wip {

namespace {

constexpr Role kLegRoles[2][3] = {{Role::LeftHip, Role::LeftKnee, Role::LeftAnkle},
                                  {Role::RightHip, Role::RightKnee, Role::RightAnkle}};

// Ankle height above the lowest point of its foot (toes, end sites), rest pose.
double ankle_above_sole(const Skeleton& s, std::span<const Transform> g, int ankle) {
  double sole = g[static_cast<std::size_t>(ankle)].translation.y();
  for (int j = 0; j < s.joint_count(); ++j)
    if (s.is_ancestor(ankle, j))
      sole = std::min({sole, g[static_cast<std::size_t>(j)].translation.y(), end_site_position(s, g, j).y()});
  return g[static_cast<std::size_t>(ankle)].translation.y() - sole;
}

// Rest poses often hold the arms out (T-pose): let the upper arms hang down
// a little away from the body, so the standing avatar looks natural.
void hang_arms(const Skeleton& s, Pose& pose) {
  const Role arms[2][2] = {{Role::LeftShoulder, Role::LeftElbow}, {Role::RightShoulder, Role::RightElbow}};
  for (int side = 0; side < 2; ++side) {
    const int sh = s.roles[arms[side][0]], el = s.roles[arms[side][1]];
    if (sh < 0 || el < 0) continue;
    std::vector<Transform> g(static_cast<std::size_t>(s.joint_count()));
    forward_kinematics(s, pose, g);
    const Vec3 bone = g[static_cast<std::size_t>(el)].translation - g[static_cast<std::size_t>(sh)].translation;
    if (bone.norm() < 1e-9) continue;
    const Vec3 want = Vec3(side == 0 ? 0.15 : -0.15, -1.0, 0.0).normalized();  // +x is the character's left
    const Quat turn = Quat::FromTwoVectors(bone, want);
    const Quat model = turn * g[static_cast<std::size_t>(sh)].rotation;
    const int parent = s.parents[static_cast<std::size_t>(sh)];
    pose.rotations[static_cast<std::size_t>(sh)] =
        parent < 0 ? model : (g[static_cast<std::size_t>(parent)].rotation.conjugate() * model).normalized();
  }
}

double approach(double current, double target, double dt, double tau) {
  if (!(tau > 0)) return target;
  return current + (target - current) * (1 - std::exp(-dt / tau));
}

}  // namespace

WipModel make_wip_model(const Skeleton& avatar, const WipParams& params, ConstPoseRef upper_body) {
  WipModel m;
  m.skeleton = avatar;
  m.params = params;
  std::string missing;
  for (const auto& leg : kLegRoles)
    for (Role r : leg)
      if (!m.skeleton.roles.has(r)) missing += (missing.empty() ? "" : ", ") + std::string(role_name(r));
  if (!missing.empty())
    throw Error("avatar skeleton has no usable legs: joint roles " + missing +
                " not found (walking-in-place needs hip, knee and ankle joints on both sides)");
  for (int f = 0; f < 2; ++f) m.legs[f] = {m.skeleton.roles[kLegRoles[f][0]], m.skeleton.roles[kLegRoles[f][1]],
                                           m.skeleton.roles[kLegRoles[f][2]]};
  const BodyMeasures body = measure_body(m.skeleton);
  if (!(body.leg_length > 0.05))
    throw Error("avatar skeleton: leg length " + std::to_string(body.leg_length) + " m is not usable");
  m.leg_length = body.leg_length;
  const auto& mp = params.mapping;
  m.scale = m.leg_length / mp.reference_leg;
  m.shape.S = mp.step_length * m.scale;
  m.shape.H = mp.user_step_height;
  if (!(m.shape.H > 0) || !(params.signal.rate > 0) || !(params.signal.cutoff > 0))
    throw Error("walking-in-place parameters: step height, sample rate and cutoff must be positive");

  m.base_pose = Pose(m.skeleton);
  std::vector<Transform> g(static_cast<std::size_t>(m.skeleton.joint_count()));
  forward_kinematics(m.skeleton, m.base_pose, g);
  const Vec3 root = g[0].translation;
  for (int f = 0; f < 2; ++f) {
    m.ankle_height[f] = ankle_above_sole(m.skeleton, g, m.legs[f].end);
    const Vec3 hip = g[static_cast<std::size_t>(m.legs[f].root)].translation - root;
    m.foot_offset[f] = Vec3(hip.x(), 0, hip.z());
    m.foot_rotation[f] = g[static_cast<std::size_t>(m.legs[f].end)].rotation;
  }
  m.root_height = body.hip_height - mp.knee_bend * m.leg_length;
  if (upper_body.joint_count() == m.skeleton.joint_count()) {
    // Upper body from the given pose: everything above the pelvis (the root
    // keeps the heading, the legs are solved every frame).
    for (int j = 1; j < m.skeleton.joint_count(); ++j) {
      bool leg = false;
      for (int f = 0; f < 2; ++f) leg |= m.skeleton.is_ancestor(m.legs[f].root, j);
      bool hip_side = false;  // joints between the pelvis and a hip (CMU's LHipJoint)
      for (int f = 0; f < 2; ++f) hip_side |= m.skeleton.is_ancestor(j, m.legs[f].root);
      if (!leg && !hip_side) m.base_pose.rotations[static_cast<std::size_t>(j)] = upper_body.rotations[static_cast<std::size_t>(j)];
    }
  } else {
    hang_arms(m.skeleton, m.base_pose);
  }
  m.base_pose.translations[0] = Vec3(0, m.root_height, 0);
  return m;
}

WipWorkspace make_workspace(const WipModel& model) {
  WipWorkspace ws;
  ws.pose = model.base_pose;
  ws.model.resize(static_cast<std::size_t>(model.skeleton.joint_count()));
  reset(model, ws);
  return ws;
}

void reset(const WipModel& model, WipWorkspace& ws) {
  const auto& p = model.params;
  for (int f = 0; f < 2; ++f) {
    ws.feet[f].init(p.signal);
    ws.gait[f].init(p.gait);
  }
  ws.step_speed.reset();
  ws.step_speed.gain = p.mapping.speed_gain;
  ws.frequency_speed.reset();
  ws.frequency_speed.stride_per_step = p.mapping.stride_per_step;
  if (ws.custom_speed) ws.custom_speed->reset();
  ws.started = ws.walking = false;
  ws.driver = -1;
  ws.kind = StepKind::None;
  ws.last_time = ws.ds_time = ws.dh = ws.speed = ws.distance = 0;
  ws.z_target[0] = ws.z_target[1] = ws.z[0] = ws.z[1] = 0;
  ws.gap[0] = ws.gap[1] = ws.gap_up[0] = ws.gap_up[1] = 0;
  ws.h_off = 0;
  ws.h_switch = 1;
  ws.root_xz = Vec3::Zero();
  ws.frame = WipFrame{};
}

void set_floor(WipWorkspace& ws, double left, double right) {
  ws.feet[0].floor = left;
  ws.feet[1].floor = right;
  ws.feet[0].has_floor = ws.feet[1].has_floor = true;
}

namespace {

// The equations' height input for foot f: clamped to [0, H], optionally
// normalised by the user's running apex estimate.
// Ascending, the swing's apex is not known yet: use the running estimate.
// Descending, use this swing's own apex, so the descending branch starts at
// h = H exactly where the ascending one ended (no jump at mid-swing).
double equation_height(const WipModel& m, const WipWorkspace& ws, int f) {
  const double h = std::max(ws.feet[f].h, 0.0);
  if (!m.params.mapping.normalise_height) return std::min(h, m.shape.H);
  const GaitMachine& g = ws.gait[f];
  const double apex = g.phase == GaitPhase::InitialSwing ? g.apex_estimate : g.apex;
  return std::min(h * m.shape.H / std::max(apex, m.params.gait.min_h1), m.shape.H);
}

// Starts, drives, finishes and stops steps (equations 1-4 and the stop rule).
void update_depth_targets(const WipModel& m, WipWorkspace& ws, const unsigned ev[2], double dt) {
  const bool both_down = !in_swing(ws.gait[0].phase) && !in_swing(ws.gait[1].phase);
  ws.ds_time = both_down ? ws.ds_time + dt : 0;
  const double S = m.shape.S;
  // The driving foot landed: the step ends with it in front.
  if (ws.driver >= 0 && !in_swing(ws.gait[ws.driver].phase)) {
    ws.z_target[ws.driver] = 0.5 * S;
    ws.z_target[1 - ws.driver] = -0.5 * S;
    const int other = 1 - ws.driver;
    ws.driver = -1;
    // Both feet were up: the other one takes over mid-swing.
    if (in_swing(ws.gait[other].phase)) {
      ws.driver = other;
      ws.kind = StepKind::Consecutive;
      // Its foot-off and mid-swing passed unseen: no gaps to fade (the smoothing takes the jump).
      ws.gap[0] = ws.gap[1] = ws.gap_up[0] = ws.gap_up[1] = 0;
    }
  }
  // A foot lifted while no step runs: a new step (first one after a stop).
  for (int f = 0; f < 2 && ws.driver < 0; ++f)
    if (ev[f] & kEventFootOff) {
      ws.driver = f;
      ws.kind = ws.walking ? StepKind::Consecutive : StepKind::First;
      ws.walking = true;
    }
  if (ws.driver >= 0) {
    const int s = ws.driver, o = 1 - s;
    const bool up = ws.gait[s].phase == GaitPhase::InitialSwing;
    const double h = equation_height(m, ws, s);
    double zs, zo;
    if (ws.kind == StepKind::First) {
      zs = first_step_swing(m.shape, h, up);
      zo = first_step_support(m.shape, h, up);
    } else {
      zs = next_step_swing(m.shape, h, up);
      zo = next_step_support(m.shape, h, up);
    }
    // The branches meet only at h = H; mid-swing is detected a little before
    // the apex and the running apex estimate is not exact, so the descending
    // branch starts with the gap left at the switch and closes it in
    // proportion to the remaining height (the foot still lands exactly on
    // the equations' final value).
    // Likewise the foot-off is detected at H1, not at h = 0: the ascending
    // branch starts from where the feet are and fades that gap out by the apex.
    if (ev[s] & kEventFootOff) {
      ws.gap_up[s] = ws.z_target[s] - zs;
      ws.gap_up[o] = ws.z_target[o] - zo;
      ws.h_off = ws.feet[s].h;
      ws.gap[0] = ws.gap[1] = 0;
    }
    if (up) {
      const double apex = std::max(ws.gait[s].apex_estimate, ws.h_off + 1e-3);
      const double fade_up = 1 - std::clamp((ws.feet[s].h - ws.h_off) / (apex - ws.h_off), 0.0, 1.0);
      zs += fade_up * ws.gap_up[s];
      zo += fade_up * ws.gap_up[o];
    }
    if (ev[s] & kEventMidSwing) {
      ws.gap[s] = ws.z_target[s] - zs;
      ws.gap[o] = ws.z_target[o] - zo;
      ws.h_switch = std::max(ws.feet[s].h, m.params.gait.min_h1);
    }
    const double fade = up ? 0.0 : std::clamp(ws.feet[s].h / ws.h_switch, 0.0, 1.0);
    ws.z_target[s] = zs + fade * ws.gap[s];
    ws.z_target[o] = zo + fade * ws.gap[o];
  }
  if (ws.walking && ws.driver < 0 && ws.ds_time > m.params.mapping.stop_time) {
    ws.walking = false;
    ws.kind = StepKind::None;
    ws.z_target[0] = ws.z_target[1] = 0;
  }
}

void solve_pose(const WipModel& m, WipWorkspace& ws, const double lift[2]) {
  const auto& mp = m.params.mapping;
  const Quat yaw(Eigen::AngleAxisd(ws.heading, Vec3::UnitY()));
  std::copy(m.base_pose.rotations.begin(), m.base_pose.rotations.end(), ws.pose.rotations.begin());
  std::copy(m.base_pose.translations.begin(), m.base_pose.translations.end(), ws.pose.translations.begin());
  const Vec3 root(ws.root_xz.x(), m.root_height - ws.dh, ws.root_xz.z());
  ws.pose.translations[0] = root;
  ws.pose.rotations[0] = yaw * m.base_pose.rotations[0];
  forward_kinematics(m.skeleton, ws.pose, ws.model);
  const Vec3 forward = yaw * Vec3::UnitZ();
  for (int f = 0; f < 2; ++f) {
    const Vec3 local(m.foot_offset[f].x(), 0, m.foot_offset[f].z() + ws.z[f]);
    Vec3 target = yaw * local;
    target.x() += root.x();
    target.z() += root.z();
    target.y() = m.ankle_height[f] + lift[f];
    ik::TwoBoneTarget t;
    t.position = target;
    const Vec3 hip = ws.model[static_cast<std::size_t>(m.legs[f].root)].translation;
    t.hint = 0.5 * (hip + target) + mp.hint_forward * m.scale * forward;
    t.rotation = yaw * m.foot_rotation[f];
    t.rotation_weight = mp.feet_flat ? 1.0 : 0.0;
    ik::solve_two_bone(m.skeleton, m.legs[f], t, ws.pose.ref(), ws.model);
    ws.frame.target_world[f] = target;
  }
}

}  // namespace

const WipFrame& update(const WipModel& m, const TrackerSample& sample, WipWorkspace& ws) {
  const auto& p = m.params;
  double dt = 1.0 / p.signal.rate;
  if (ws.started) {
    if (!(sample.time > ws.last_time)) return ws.frame;  // out of order or repeated: ignore
    dt = std::min(sample.time - ws.last_time, 0.5);
  }
  ws.started = true;
  ws.last_time = sample.time;

  unsigned ev[2];
  for (int f = 0; f < 2; ++f) {
    const bool support = !in_swing(ws.gait[f].phase);
    ws.feet[f].push(p.signal, sample.ankle[f].y(), sample.valid[f], dt, support);
    ev[f] = ws.gait[f].update(p.gait, ws.feet[f].h, ws.feet[f].v, ws.feet[f].confidence, dt);
  }
  update_depth_targets(m, ws, ev, dt);

  // Smooth the targets (frame-rate independent form of the document's lerp).
  const auto& mp = p.mapping;
  for (int f = 0; f < 2; ++f) ws.z[f] = approach(ws.z[f], ws.z_target[f], dt, mp.smoothing_tau);
  // Eq. 5-7: the body drops with the trailing foot's depth while walking. The
  // leading foot can reach further than the trailing one (the strike
  // overshoot of eq. 3), so the farther of the two sets the drop: otherwise
  // that leg would be out of reach and lock straight.
  const double z_far = std::max({-ws.z[0], -ws.z[1], ws.z[0], ws.z[1]});
  const double dh_target = ws.walking ? body_drop(m.leg_length, z_far) : 0.0;
  ws.dh = approach(ws.dh, dh_target, dt, mp.body_tau);
  // Eq. 8: swinging feet lift by lift_scale * h (scaled to the avatar).
  double y_local[2], lift[2];
  for (int f = 0; f < 2; ++f) {
    const double h = std::clamp(ws.feet[f].h, 0.0, m.shape.H);
    const double up = in_swing(ws.gait[f].phase) ? mp.lift_scale * h * m.scale : 0.0;
    y_local[f] = up + ws.dh;
    lift[f] = up;
  }

  // Forward speed.
  SpeedEstimator* est = ws.custom_speed ? ws.custom_speed
                        : mp.speed_model == SpeedModel::StepSpeed ? static_cast<SpeedEstimator*>(&ws.step_speed)
                                                                  : static_cast<SpeedEstimator*>(&ws.frequency_speed);
  for (int f = 0; f < 2; ++f) est->observe({sample.time, dt, f, ev[f], ws.feet[f].v, ws.walking});
  const double target_speed = std::clamp(est->target_speed(sample.time), 0.0, mp.max_speed);
  ws.speed = approach(ws.speed, target_speed, dt, mp.speed_tau);
  const Vec3 forward(std::sin(ws.heading), 0, std::cos(ws.heading));
  ws.root_xz += forward * ws.speed * dt;
  ws.distance += ws.speed * dt;

  solve_pose(m, ws, lift);

  WipFrame& fr = ws.frame;
  fr.time = sample.time;
  for (int f = 0; f < 2; ++f) {
    fr.phase[f] = ws.gait[f].phase;
    fr.events[f] = ev[f];
    fr.h[f] = ws.feet[f].h;
    fr.v[f] = ws.feet[f].v;
    fr.confidence[f] = ws.feet[f].confidence;
    fr.h1[f] = ws.gait[f].h1(p.gait);
    fr.z_target[f] = ws.z_target[f];
    fr.z[f] = ws.z[f];
    fr.y[f] = y_local[f];
  }
  fr.root_offset = -ws.dh;
  fr.speed = ws.speed;
  fr.distance = ws.distance;
  fr.root_position = ws.pose.translations[0];
  fr.walking = ws.walking;
  fr.driver = ws.driver;
  fr.kind = ws.kind;
  fr.double_support_time = ws.ds_time;
  return fr;
}

FloorCalibration calibrate_floor(std::span<const TrackerSample> samples, double seconds, double max_std) {
  FloorCalibration c;
  if (samples.empty()) {
    c.message = "no tracker samples to calibrate the floor from";
    return c;
  }
  const double t0 = samples.front().time;
  int total = 0;
  for (int f = 0; f < 2; ++f) {
    double sum = 0, sum2 = 0;
    int n = 0;
    total = 0;
    for (const auto& s : samples) {
      if (s.time - t0 > seconds) break;
      ++total;
      if (!s.valid[f] || !std::isfinite(s.ankle[f].y())) continue;
      sum += s.ankle[f].y();
      sum2 += s.ankle[f].y() * s.ankle[f].y();
      ++n;
    }
    const char* side = f == 0 ? "left" : "right";
    if (n < std::max(3, total / 2)) {
      c.message = std::string("cannot calibrate the floor: only ") + std::to_string(n) + " of " + std::to_string(total) +
                  " " + side + " ankle samples in the first " + std::to_string(seconds).substr(0, 4) + " s are valid";
      return c;
    }
    c.floor[f] = sum / n;
    c.spread[f] = std::sqrt(std::max(0.0, sum2 / n - c.floor[f] * c.floor[f]));
  }
  for (int f = 0; f < 2; ++f)
    if (c.spread[f] > max_std) {
      char buf[320];
      std::snprintf(buf, sizeof buf,
                    "cannot calibrate the floor: the user is not standing still during the first %.1f s "
                    "(%s ankle height varies by %.1f cm std, limit %.1f cm). Stand still for the calibration, "
                    "or skip it (rolling floor).",
                    seconds, f == 0 ? "left" : "right", 100 * c.spread[f], 100 * max_std);
      c.message = buf;
      return c;
    }
  c.ok = true;
  char buf[160];
  std::snprintf(buf, sizeof buf, "floor calibrated over %.1f s: ankle heights %.3f / %.3f m (std %.1f / %.1f cm)", seconds,
                c.floor[0], c.floor[1], 100 * c.spread[0], 100 * c.spread[1]);
  c.message = buf;
  return c;
}

WipRun run_wip(const WipModel& model, std::span<const TrackerSample> samples, const RunOptions& opt) {
  WipRun run;
  WipWorkspace ws = make_workspace(model);
  if (opt.calibrate) {
    run.calibration = calibrate_floor(samples, opt.calibration_seconds);
    if (!run.calibration.ok) throw Error(run.calibration.message);
    set_floor(ws, run.calibration.floor[0], run.calibration.floor[1]);
  }
  run.frames.reserve(samples.size());
  if (opt.keep_poses) run.motion = Motion(model.skeleton, model.params.signal.rate, 0);
  for (const auto& s : samples) {
    const double before = ws.started ? ws.last_time : -1e300;
    if (!(s.time > before)) continue;
    run.frames.push_back(update(model, s, ws));
    if (opt.keep_poses) run.motion.push_back(ws.pose);
  }
  return run;
}

}  // namespace legwork::wip
