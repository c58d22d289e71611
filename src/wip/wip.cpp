// Walking-in-place runtime: signal -> gait machines -> equations -> IK.
#include <legwork/wip/wip.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/rotation.hpp>

#include <algorithm>
#include <cmath>
#include <string>

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

// Upper body from the given pose: everything above the pelvis (the root
// keeps the heading, the legs are solved every frame).
void copy_upper_body(const Skeleton& s, const ik::TwoBoneChain (&legs)[2], ConstPoseRef upper_body, Pose& pose) {
  for (int j = 1; j < s.joint_count(); ++j) {
    bool leg = false, hip_side = false;  // hip_side: joints between the pelvis and a hip (CMU's LHipJoint)
    for (int f = 0; f < 2; ++f) {
      leg |= s.is_ancestor(legs[f].root, j);
      hip_side |= s.is_ancestor(j, legs[f].root);
    }
    if (!leg && !hip_side) pose.rotations[static_cast<std::size_t>(j)] = upper_body.rotations[static_cast<std::size_t>(j)];
  }
}

double approach(double current, double target, double dt, double tau) {
  if (!(tau > 0)) return target;
  return current + (target - current) * (1 - std::exp(-dt / tau));
}


}  // namespace

double step_speed_gain(const Settings& s) {
  if (s.mapping.speed_gain > 0) return s.mapping.speed_gain;
  return s.gait.detector == StepDetector::Adaptive ? kAdaptiveSpeedGain : kDocumentSpeedGain;
}

Model make_model(const Skeleton& avatar, const Settings& settings, ConstPoseRef upper_body,
                 const LearnedMapping* learned) {
  Model m;
  if (settings.mapping.depth == DepthMapping::Learned) {
    if (!learned)
      throw Error("walking-in-place settings: the learned depth mapping needs a learned table "
                  "(wip::read_learned_mapping, or `legwork wip learn`)");
    m.learned_ = *learned;
    m.has_learned_ = true;
  }
  m.skeleton_ = avatar;
  m.settings_ = settings;
  const Skeleton& s = m.skeleton_;
  std::string missing;
  for (const auto& leg : kLegRoles)
    for (Role r : leg)
      if (!s.roles.has(r)) missing += (missing.empty() ? "" : ", ") + std::string(role_name(r));
  if (!missing.empty())
    throw Error("avatar skeleton has no usable legs: joint roles " + missing +
                " not found (walking-in-place needs hip, knee and ankle joints on both sides)");
  ik::TwoBoneChain chains[2];
  for (int f = 0; f < 2; ++f)
    chains[f] = {s.roles[kLegRoles[f][0]], s.roles[kLegRoles[f][1]], s.roles[kLegRoles[f][2]]};
  const BodyMeasures body = measure_body(s);
  if (!(body.leg_length > 0.05))
    throw Error("avatar skeleton: leg length " + std::to_string(body.leg_length) + " m is not usable");
  m.leg_length_ = body.leg_length;
  const auto& mp = settings.mapping;
  m.scale_ = m.leg_length_ / mp.reference_leg;
  m.shape_.S = mp.step_length * m.scale_;
  m.shape_.H = mp.user_step_height;
  if (!(m.shape_.H > 0) || !(settings.signal.rate > 0) || !(settings.signal.cutoff > 0) || !(mp.reference_leg > 0))
    throw Error("walking-in-place settings: step height, reference leg, sample rate and cutoff must be positive");
  if (!(mp.speed_gain >= 0))
    throw Error("walking-in-place settings: speed_gain " + std::to_string(mp.speed_gain) +
                " must be >= 0 (0 = the detector's calibrated gain)");
  {
    const auto& g = settings.gait;
    const std::pair<const char*, double> start[] = {{"rest_time", g.rest_time},
                                                    {"rest_lift", g.rest_lift},
                                                    {"rest_rise", g.rest_rise},
                                                    {"rest_noise_factor", g.rest_noise_factor},
                                                    {"settle_time", g.settle_time},
                                                    {"min_swing_time", g.min_swing_time}};
    for (const auto& [name, value] : start)
      if (!(value >= 0) || !std::isfinite(value))
        throw Error(std::string("walking-in-place settings: gait.") + name + " " + std::to_string(value) +
                    " must be finite and >= 0 (0 = off)");
    if (g.min_swing_time > 1.0)
      throw Error("walking-in-place settings: gait.min_swing_time " + std::to_string(g.min_swing_time) +
                  " s must be <= 1 (a swing shorter than that could never land)");
  }

  m.base_pose_ = Pose(s);
  std::vector<Transform> g(static_cast<std::size_t>(s.joint_count()));
  forward_kinematics(s, m.base_pose_, g);
  const Vec3 root = g[0].translation;
  for (int f = 0; f < 2; ++f) {
    Model::Leg& leg = m.legs_[f];
    leg.chain = chains[f];
    leg.ankle_height = ankle_above_sole(s, g, chains[f].end);
    const Vec3 hip = g[static_cast<std::size_t>(chains[f].root)].translation - root;
    leg.foot_offset = Vec3(hip.x(), 0, hip.z());
    leg.foot_rotation = g[static_cast<std::size_t>(chains[f].end)].rotation;
  }
  m.root_height_ = body.hip_height - mp.knee_bend * m.leg_length_;
  if (upper_body.joint_count() == s.joint_count()) copy_upper_body(s, chains, upper_body, m.base_pose_);
  else hang_arms(s, m.base_pose_);
  m.base_pose_.translations[0] = Vec3(0, m.root_height_, 0);
  return m;
}

State::State(const Model& model) : model_space(static_cast<std::size_t>(model.skeleton().joint_count())) {
  reset(model, *this);
}

namespace {

// Filters, gait machines, speed and step mapping back to a standing start.
void reset_motion(const Model& model, State& st) {
  const auto& p = model.settings();
  for (int f = 0; f < 2; ++f) {
    st.feet[f].init(p.signal);
    st.feet[f].has_floor = st.calibrated;
    st.feet[f].floor = st.calibrated ? st.calibrated_floor[f] : 0.0;
    st.gait[f].init(p.gait);
  }
  st.step_speed.reset();
  st.step_speed.gain = step_speed_gain(p);
  st.frequency_speed.reset();
  st.frequency_speed.stride_per_step = p.mapping.stride_per_step;
  st.walking = false;
  st.driver = -1;
  st.kind = StepKind::None;
  st.ds_time = st.dh = st.speed = 0;
  st.z_target[0] = st.z_target[1] = st.z[0] = st.z[1] = 0;
  st.gap[0] = st.gap[1] = st.gap_up[0] = st.gap_up[1] = 0;
  st.h_off = 0;
  st.h_switch = 1;
  st.cycle[0] = st.cycle[1] = 0;
  st.lead = -1;
  st.last_off[0] = st.last_off[1] = -1e9;
  st.last_strike = -1e9;
  st.stride_period = LearnedMapping::kDefaultStridePeriod;
}

}  // namespace

void reset(const Model& model, State& st) {
  st.clock.reset();
  st.calibrated = false;
  st.calibrated_floor[0] = st.calibrated_floor[1] = 0;
  st.heading = 0;
  st.heading_seen = false;
  st.heading_time = 0;
  st.turn_rate = 0;
  st.distance = 0;
  st.root_xz = Vec3::Zero();
  reset_motion(model, st);
}

void set_floor(State& st, double left, double right) {
  st.calibrated = true;
  st.calibrated_floor[0] = left;
  st.calibrated_floor[1] = right;
  for (int f = 0; f < 2; ++f) {
    st.feet[f].floor = st.calibrated_floor[f];
    st.feet[f].has_floor = true;
  }
}

namespace {

// The equations' height input for foot f: clamped to [0, H], optionally
// normalised by the user's running apex estimate.
// Ascending, the swing's apex is not known yet: use the running estimate.
// Descending, use this swing's own apex, so the descending branch starts at
// h = H exactly where the ascending one ended (no jump at mid-swing).
double equation_height(const Model& m, const State& st, int f) {
  const double h = std::max(st.feet[f].h, 0.0);
  const StepShape& k = m.shape();
  if (!m.settings().mapping.normalise_height) return std::min(h, k.H);
  const GaitMachine& g = st.gait[f];
  const double apex = g.phase == GaitPhase::InitialSwing ? g.apex_estimate : g.apex;
  return std::min(h * k.H / std::max(apex, m.settings().gait.min_h1), k.H);
}

// The driving foot landed: the step ends with it in front; if the other foot
// is already up it takes over mid-swing.
void finish_step(State& st, double S) {
  st.z_target[st.driver] = 0.5 * S;
  st.z_target[1 - st.driver] = -0.5 * S;
  const int other = 1 - st.driver;
  st.driver = -1;
  if (in_swing(st.gait[other].phase)) {
    st.driver = other;
    st.kind = StepKind::Consecutive;
    // Its foot-off and mid-swing passed unseen: no gaps to fade (the smoothing takes the jump).
    st.gap[0] = st.gap[1] = st.gap_up[0] = st.gap_up[1] = 0;
  }
}

// Drives the running step's depth targets from the swinging foot's height.
void drive_step(const Model& m, State& st, const unsigned ev[2]) {
  const int s = st.driver, o = 1 - s;
  const bool up = st.gait[s].phase == GaitPhase::InitialSwing;
  const double h = equation_height(m, st, s);
  double zs, zo;
  if (st.kind == StepKind::First) {
    zs = first_step_swing(m.shape(), h, up);
    zo = first_step_support(m.shape(), h, up);
  } else {
    zs = next_step_swing(m.shape(), h, up);
    zo = next_step_support(m.shape(), h, up);
  }
  // The branches meet only at h = H; mid-swing is detected a little before
  // the apex and the running apex estimate is not exact, so the descending
  // branch starts with the gap left at the switch and closes it in
  // proportion to the remaining height (the foot still lands exactly on
  // the equations' final value).
  // Likewise the foot-off is detected at H1, not at h = 0: the ascending
  // branch starts from where the feet are and fades that gap out by the apex.
  if (ev[s] & kEventFootOff) {
    st.gap_up[s] = st.z_target[s] - zs;
    st.gap_up[o] = st.z_target[o] - zo;
    st.h_off = st.feet[s].h;
    st.gap[0] = st.gap[1] = 0;
  }
  if (up) {
    const double apex = std::max(st.gait[s].apex_estimate, st.h_off + 1e-3);
    const double fade_up = 1 - std::clamp((st.feet[s].h - st.h_off) / (apex - st.h_off), 0.0, 1.0);
    zs += fade_up * st.gap_up[s];
    zo += fade_up * st.gap_up[o];
  }
  if (ev[s] & kEventMidSwing) {
    st.gap[s] = st.z_target[s] - zs;
    st.gap[o] = st.z_target[o] - zo;
    st.h_switch = std::max(st.feet[s].h, m.settings().gait.min_h1);
  }
  const double fade = up ? 0.0 : std::clamp(st.feet[s].h / st.h_switch, 0.0, 1.0);
  st.z_target[s] = zs + fade * st.gap[s];
  st.z_target[o] = zo + fade * st.gap[o];
}

// The learned mapping's inputs (always kept, for Info and training) and,
// with the learned mapping, its depth targets while walking.
void learned_depth_targets(const Model& m, State& st, const unsigned ev[2], double time) {
  const auto& p = m.settings();
  for (int f = 0; f < 2; ++f) {
    if (ev[f] & kEventFootStrike) st.lead = f, st.last_strike = time;
    st.cycle[f] = cycle_coordinate(st.gait[f], p.gait, st.feet[f].h);
    if (!(ev[f] & kEventFootOff)) continue;
    // Stride period: the running mean of each foot's foot-off to foot-off time.
    const double interval = time - st.last_off[f];
    if (interval > 0.3 && interval < LearnedMapping::kMaxStridePeriod)
      st.stride_period += 0.3 * (interval - st.stride_period);
    st.last_off[f] = time;
  }
  const LearnedMapping* table = m.learned();
  if (!table || !st.walking) return;
  const double apex = 0.5 * (st.gait[0].apex_estimate + st.gait[1].apex_estimate);
  for (int f = 0; f < 2; ++f) {
    const int lead = st.lead < 0 ? -1 : st.lead == f ? 1 : 0;
    st.z_target[f] =
        m.leg_length() *
        table->depth(st.cycle[f], st.cycle[1 - f], lead, time - st.last_strike, apex, 1 / st.stride_period, st.turn_rate);
  }
}

// Starts, drives, finishes and stops steps (equations 1-4 and the stop rule).
void update_depth_targets(const Model& m, State& st, const unsigned ev[2], double dt) {
  const bool both_down = !in_swing(st.gait[0].phase) && !in_swing(st.gait[1].phase);
  st.ds_time = both_down ? st.ds_time + dt : 0;
  if (st.driver >= 0 && !in_swing(st.gait[st.driver].phase)) finish_step(st, m.shape().S);
  // A foot lifted while no step runs: a new step (first one after a stop).
  for (int f = 0; f < 2 && st.driver < 0; ++f)
    if (ev[f] & kEventFootOff) {
      st.driver = f;
      st.kind = st.walking ? StepKind::Consecutive : StepKind::First;
      st.walking = true;
    }
  if (st.driver >= 0) drive_step(m, st, ev);
  if (st.walking && st.driver < 0 && st.ds_time > m.settings().mapping.stop_time) {
    st.walking = false;
    st.kind = StepKind::None;
    st.z_target[0] = st.z_target[1] = 0;
  }
}

// The root's world position and each ankle's IK target (world) for this frame's state.
Vec3 leg_targets(const Model& m, const State& st, const double lift[2], Vec3 target_world[2]) {
  const Quat yaw = yaw_rotation(st.heading);
  const Vec3 root(st.root_xz.x(), m.root_height() - st.dh, st.root_xz.z());
  for (int f = 0; f < 2; ++f) {
    const Model::Leg& leg = m.leg(f);
    const Vec3 local(leg.foot_offset.x(), 0, leg.foot_offset.z() + st.z[f]);
    Vec3 target = yaw * local;
    target.x() += root.x();
    target.z() += root.z();
    target.y() = leg.ankle_height + lift[f];
    target_world[f] = target;
  }
  return root;
}

// The avatar on the base pose, its root at `root`, each leg's two-bone IK on its target.
void solve_pose(const Model& m, State& st, const Vec3& root, const Vec3 target_world[2], PoseRef out) {
  const auto& mp = m.settings().mapping;
  const Quat yaw = yaw_rotation(st.heading);
  const Pose& base = m.base_pose();
  std::copy(base.rotations.begin(), base.rotations.end(), out.rotations.begin());
  std::copy(base.translations.begin(), base.translations.end(), out.translations.begin());
  out.translations[0] = root;
  out.rotations[0] = yaw * base.rotations[0];
  forward_kinematics(m.skeleton(), out, st.model_space);
  const Vec3 forward = yaw * Vec3::UnitZ();
  for (int f = 0; f < 2; ++f) {
    const Model::Leg& leg = m.leg(f);
    ik::TwoBoneTarget t;
    t.position = target_world[f];
    const Vec3 hip = st.model_space[static_cast<std::size_t>(leg.chain.root)].translation;
    t.hint = 0.5 * (hip + t.position) + mp.hint_forward * m.scale() * forward;
    t.rotation = yaw * leg.foot_rotation;
    t.rotation_weight = mp.feet_flat ? 1.0 : 0.0;
    ik::solve_two_bone(m.skeleton(), leg.chain, t, out, st.model_space);
  }
}

// Signal processing and gait machines for both feet; returns true when both were usable.
bool track_feet(const Model& m, const TrackerFrame& frame, State& st, double dt, unsigned ev[2]) {
  const auto& p = m.settings();
  bool all = true;
  for (int f = 0; f < 2; ++f) {
    const DevicePose& d = frame.foot(f);
    const bool ok = usable(d);
    all = all && ok;
    const bool support = !in_swing(st.gait[f].phase);
    FootSignal& s = st.feet[f];
    s.push(p.signal, ok ? d.position.y() : 0.0, ok, dt, support);
    if (p.gait.detector == StepDetector::Adaptive) {
      st.gait[f].noise = s.noise;
      st.gait[f].rest = st.ds_time;  // both feet down until the last frame
      ev[f] = st.gait[f].update(p.gait, s.hd, s.vd, s.confidence, dt);
    } else {
      ev[f] = st.gait[f].update(p.gait, s.h, s.v, s.confidence, dt);
    }
  }
  return all;
}

// Forward speed (the chosen estimator, capped and smoothed) and progression.
void advance_body(const Model& m, State& st, double time, double dt, const unsigned ev[2]) {
  const auto& mp = m.settings().mapping;
  SpeedEstimator& est = mp.speed_model == SpeedModel::StepSpeed ? static_cast<SpeedEstimator&>(st.step_speed)
                                                                 : static_cast<SpeedEstimator&>(st.frequency_speed);
  for (int f = 0; f < 2; ++f) est.observe({time, dt, f, ev[f], st.feet[f].v, st.walking});
  const double target_speed = std::clamp(est.target_speed(time), 0.0, mp.max_speed);
  st.speed = approach(st.speed, target_speed, dt, mp.speed_tau);
  const Vec3 forward(std::sin(st.heading), 0, std::cos(st.heading));
  st.root_xz += forward * st.speed * dt;
  st.distance += st.speed * dt;
}

void fill_info(const Model& m, const State& st, double time, const unsigned ev[2], const double y_local[2],
               const Vec3& root, const Vec3 target_world[2], Info& fr) {
  fr.time = time;
  for (int f = 0; f < 2; ++f) {
    fr.phase[f] = st.gait[f].phase;
    fr.events[f] = ev[f];
    fr.h[f] = st.feet[f].h;
    fr.v[f] = st.feet[f].v;
    fr.confidence[f] = st.feet[f].confidence;
    fr.h1[f] = st.gait[f].h1(m.settings().gait);
    fr.z_target[f] = st.z_target[f];
    fr.z[f] = st.z[f];
    fr.y[f] = y_local[f];
    fr.cycle[f] = st.cycle[f];
    fr.apex_estimate[f] = st.gait[f].apex_estimate;
    fr.target_world[f] = target_world[f];
  }
  fr.root_offset = -st.dh;
  fr.speed = st.speed;
  fr.distance = st.distance;
  fr.heading = st.heading;
  fr.turn_rate = st.turn_rate;
  fr.root_position = root;
  fr.walking = st.walking;
  fr.driver = st.driver;
  fr.lead = st.lead;
  fr.stride_period = st.stride_period;
  fr.since_strike = time - st.last_strike;
  fr.kind = st.kind;
  fr.double_support_time = st.ds_time;
}

}  // namespace

UpdateStatus update(const Model& m, const TrackerFrame& frame, State& st, PoseRef out, Info* info) {
  if ((out.joint_count() != 0 && out.joint_count() != m.skeleton().joint_count()) ||
      out.translations.size() != out.rotations.size() ||
      st.model_space.size() != static_cast<std::size_t>(m.skeleton().joint_count()))
    return UpdateStatus::Rejected;  // not this model's pose or state: nothing to do
  const FrameClock::Step step = st.clock.advance(frame.time);
  if (step.verdict == FrameClock::Verdict::Reject) return UpdateStatus::Rejected;
  const bool restarted = step.verdict == FrameClock::Verdict::Restart;
  if (restarted) reset_motion(m, st);
  const auto& p = m.settings();
  // The first frame (and the first after a restart) integrates one nominal sample period.
  const double dt = step.dt > 0 ? std::min(step.dt, p.mapping.max_dt) : 1.0 / p.signal.rate;
  if (usable(frame.head())) {
    const double yaw = yaw_of(frame.head().rotation, st.heading);
    // The head's turning speed (the learned mapping shortens steps in turns).
    // Over the time since the last usable head sample (a dropout does not
    // read as a fast turn); a restart's time jump back is skipped.
    const double elapsed = frame.time - st.heading_time;
    if (st.heading_seen && elapsed > 0) {
      const double rate = std::abs(wrap_angle(yaw - st.heading)) / std::max(elapsed, dt);
      if (std::isfinite(rate)) st.turn_rate += (1 - std::exp(-dt / LearnedMapping::kTurnTau)) * (rate - st.turn_rate);
    }
    st.heading = yaw;
    st.heading_time = frame.time;
    st.heading_seen = true;
  }

  unsigned ev[2];
  const bool feet_ok = track_feet(m, frame, st, dt, ev);
  update_depth_targets(m, st, ev, dt);
  learned_depth_targets(m, st, ev, frame.time);

  // Smooth the targets (frame-rate independent form of the document's lerp).
  const auto& mp = p.mapping;
  const double tau = m.learned() ? mp.learned_smoothing_tau : mp.smoothing_tau;
  for (int f = 0; f < 2; ++f) st.z[f] = approach(st.z[f], st.z_target[f], dt, tau);
  // Eq. 5-7: the body drops with the trailing foot's depth while walking. The
  // leading foot can reach further than the trailing one (the strike
  // overshoot of eq. 3), so the farther of the two sets the drop: otherwise
  // that leg would be out of reach and lock straight.
  const double z_far = std::max({-st.z[0], -st.z[1], st.z[0], st.z[1]});
  const double dh_target = st.walking ? body_drop(m.leg_length(), z_far) : 0.0;
  st.dh = approach(st.dh, dh_target, dt, mp.body_tau);
  // Eq. 8: swinging feet lift by lift_scale * h (scaled to the avatar).
  double y_local[2], lift[2];
  for (int f = 0; f < 2; ++f) {
    const double h = std::clamp(st.feet[f].h, 0.0, m.shape().H);
    lift[f] = in_swing(st.gait[f].phase) ? mp.lift_scale * h * m.scale() : 0.0;
    y_local[f] = lift[f] + st.dh;
  }
  advance_body(m, st, frame.time, dt, ev);
  Vec3 target_world[2];
  const Vec3 root = leg_targets(m, st, lift, target_world);
  if (out.joint_count() > 0) solve_pose(m, st, root, target_world, out);
  if (info) fill_info(m, st, frame.time, ev, y_local, root, target_world, *info);
  if (restarted) return UpdateStatus::Restarted;
  return feet_ok ? UpdateStatus::Ok : UpdateStatus::Degraded;
}

void describe(const Info& i, InfoFields& out) {
  add_walking(out, i.walking, i.speed, i.distance, i.heading);
  out.add("phase_left", phase_name(i.phase[0]).data());  // static, NUL-terminated literals
  out.add("phase_right", phase_name(i.phase[1]).data());
  out.add("turn_rate", i.turn_rate);
}

}  // namespace legwork::wip
