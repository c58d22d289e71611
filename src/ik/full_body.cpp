// VRIK-style full-body IK from head + two hands (see full_body.hpp).
#include <legwork/ik/full_body.hpp>
#include <legwork/core/rotation.hpp>

#include <legwork/core/fk.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace legwork::ik {
namespace {

Quat pitch_rotation(double pitch) { return Quat(Eigen::AngleAxisd(pitch, Vec3::UnitX())); }

// Horizontal distance from p to the segment [a, b].
double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ph = horizontal(p), ah = horizontal(a), bh = horizontal(b);
  const Vec3 ab = bh - ah;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 1e-12 ? std::clamp((ph - ah).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (ph - (ah + t * ab)).norm();
}


Quat parent_model_rotation(const Skeleton& skel, std::span<const Transform> model, int j) {
  const int p = skel.parents[static_cast<std::size_t>(j)];
  return p < 0 ? Quat::Identity() : model[static_cast<std::size_t>(p)].rotation;
}

double bone(const std::vector<Vec3>& rest, int a, int b) {
  return (rest[static_cast<std::size_t>(a)] - rest[static_cast<std::size_t>(b)]).norm();
}

std::size_t idx(int j) { return static_cast<std::size_t>(j); }

}  // namespace

// The devices this frame, as the solver reads them.
struct SolverInput {
  Vec3 head_position = Vec3::Zero();
  Quat head_rotation = Quat::Identity();
  std::array<Vec3, 2> hand_position{Vec3::Zero(), Vec3::Zero()};
  std::array<Quat, 2> hand_rotation{Quat::Identity(), Quat::Identity()};
  std::array<bool, 2> hand_valid{false, false};
};

// The stages of update(), in order. Friend of Model.
struct Solver {
  const Model& M;
  const Settings& S;
  const Skeleton& skel;
  const SolverInput& in;
  State& st;
  PoseRef out;
  std::span<Transform> model;
  bool first;
  double dt;

  static void measure_rest(Model& m);  // make_model's derived lengths
  void headings();
  double crouch_lean() const;
  void place_head();
  void torso(double lean);
  void clavicles();
  void swing_body();
  void arms();
  std::array<Vec3, 2> foot_places(const Vec3& balance, double foot_y) const;
  Vec3 landing(const std::array<Vec3, 2>& place, int s, double remaining, double duration, double foot_y) const;
  bool advance_steps(const std::array<Vec3, 2>& place, double foot_y);
  void start_step(const std::array<Vec3, 2>& place, const Vec3& balance, double foot_y);
  void locomotion();
  void legs();
};

// 1. Headings: chest between head and hands, pelvis following the chest.
void Solver::headings() {
  const double head_yaw = heading_of(in.head_rotation * Vec3::UnitZ(), first ? 0.0 : st.chest_yaw);
  double chest_yaw = head_yaw;
  if (in.hand_valid[0] && in.hand_valid[1]) {
    const Vec3 across = horizontal(in.hand_position[0] - in.hand_position[1]);  // right -> left
    const double hands_yaw = heading_of(across.cross(Vec3::UnitY()), head_yaw);
    const double d = wrap_angle(hands_yaw - head_yaw);
    // Crossed hands (|d| > 90 degrees) say nothing about the body's heading.
    if (std::abs(d) < 0.5 * kPi) chest_yaw = head_yaw + S.hands_heading_weight * std::clamp(across.norm() / 0.3, 0.0, 1.0) * d;
  }
  if (first) st.pelvis_yaw = chest_yaw;
  else st.pelvis_yaw += wrap_angle(chest_yaw - st.pelvis_yaw) * (1.0 - std::exp(-S.pelvis_turn_rate * dt));
  const double max_twist = 0.6;
  st.pelvis_yaw = chest_yaw - std::clamp(wrap_angle(chest_yaw - st.pelvis_yaw), -max_twist, max_twist);
  st.chest_yaw = chest_yaw;
}

// 2. Crouch and lean: the legs take most of a head drop down to the lowest
// pelvis height; the rest (and anything beyond) is a forward lean.
double Solver::crouch_lean() const {
  const double head_h = in.head_position.y() - S.floor_height;
  const double drop = std::max(0.0, M.head_height_ - head_h);
  const double min_pelvis = S.min_pelvis_fraction * M.pelvis_height_;
  double pelvis_h = std::max(min_pelvis, M.pelvis_height_ - S.crouch_leg_share * drop);
  if (head_h - pelvis_h > M.torso_length_) pelvis_h = head_h - M.torso_length_;
  return std::acos(std::clamp((head_h - pelvis_h) / M.torso_length_, 0.0, 1.0));
}

// The neck takes a share of the head's turn relative to the chest; then the
// body is placed so the head joint is exactly on the headset.
void Solver::place_head() {
  const auto root = idx(M.pelvis_);
  forward_kinematics(skel, out, model);
  const Quat chest = parent_model_rotation(skel, model, M.neck_.front());
  Quat delta = chest.conjugate() * in.head_rotation.normalized();
  if (delta.w() < 0) delta.coeffs() = -delta.coeffs();
  // Powers of one rotation compose exactly: the head ends on the headset's orientation.
  const double neck_part = S.neck_share / static_cast<double>(M.neck_.size());
  for (int j : M.neck_) out.rotations[idx(j)] = Quat::Identity().slerp(neck_part, delta);
  out.rotations[idx(M.head_)] = Quat::Identity().slerp(1.0 - S.neck_share, delta);
  forward_kinematics_subtree(skel, out, M.neck_.front(), model);  // only the neck and the head turned
  const Vec3 shift = in.head_position - model[idx(M.head_)].translation;
  out.translations[root] += shift;
  for (auto& t : model) t.translation += shift;
}

// 3. Torso rotations (rest elsewhere), then the neck shares the head's turn.
void Solver::torso(double lean) {
  for (int j = 0; j < out.joint_count(); ++j) {
    out.rotations[idx(j)] = Quat::Identity();
    out.translations[idx(j)] = skel.rest_offsets[idx(j)];
  }
  const auto root = idx(M.pelvis_);
  const double twist = wrap_angle(st.chest_yaw - st.pelvis_yaw);
  const double n_spine = static_cast<double>(std::max<std::size_t>(M.spine_.size(), 1));
  const double hip_lean = M.spine_.empty() ? lean : S.pelvis_lean_share * lean;
  out.rotations[root] = yaw_rotation(st.pelvis_yaw) * pitch_rotation(hip_lean);
  if (M.spine_.empty()) out.rotations[root] = yaw_rotation(st.chest_yaw) * pitch_rotation(lean);
  for (int j : M.spine_) out.rotations[idx(j)] = yaw_rotation(twist / n_spine) * pitch_rotation((lean - hip_lean) / n_spine);
  out.translations[root] = Vec3::Zero();
  place_head();
}

// Clavicles help long reaches: each swings just enough to bring its shoulder
// within reach of the hand, up to a limit.
void Solver::clavicles() {
  int swung[2] = {-1, -1};
  for (int s = 0; s < 2; ++s) {
    const int c = M.clavicle_[s];
    if (c < 0 || !in.hand_valid[idx(s)]) continue;
    const Vec3 shoulder = model[idx(M.arm_[s].root)].translation;
    const Vec3 target = in.hand_position[idx(s)];
    const double excess = (target - shoulder).norm() - 0.995 * M.arm_length_;
    if (excess <= 0) continue;
    const Vec3 cp = model[idx(c)].translation;
    const Vec3 b = shoulder - cp;
    const double len = b.norm();
    const Vec3 axis = b.cross(target - cp);
    if (len < 1e-6 || axis.norm() < 1e-9) continue;
    const double angle = std::min(S.clavicle_reach, 1.2 * excess / len);
    const Quat cm = (Quat(Eigen::AngleAxisd(angle, axis.normalized())) * model[idx(c)].rotation).normalized();
    out.rotations[idx(c)] = (parent_model_rotation(skel, model, c).conjugate() * cm).normalized();
    swung[s] = c;
  }
  // The model transforms (place_head's) change only below a swung clavicle.
  for (int c : swung)
    if (c >= 0) forward_kinematics_subtree(skel, out, c, model);
}

// Still out of reach (arms stretched overhead while lying, a long reach):
// swing the whole body about the head toward that hand, so the head stays
// on the headset and the hands stay exact.
void Solver::swing_body() {
  const auto root = idx(M.pelvis_);
  for (int iter = 0; iter < 4; ++iter) {
    double worst = 0;
    int side = -1;
    for (int s = 0; s < 2; ++s) {
      if (!in.hand_valid[idx(s)]) continue;
      const double e = (in.hand_position[idx(s)] - model[idx(M.arm_[s].root)].translation).norm() - 0.999 * M.arm_length_;
      if (e > worst) {
        worst = e;
        side = s;
      }
    }
    if (side < 0) break;
    const Vec3 head = model[idx(M.head_)].translation;
    const Vec3 arm = model[idx(M.arm_[side].root)].translation - head;
    const Vec3 axis = arm.cross(in.hand_position[idx(side)] - head);
    if (arm.norm() < 1e-6 || axis.norm() < 1e-9) break;
    const Quat swing(Eigen::AngleAxisd(std::min(S.body_reach, 1.1 * worst / arm.norm()), axis.normalized()));
    out.rotations[root] = (swing * out.rotations[root]).normalized();
    out.translations[root] = head + swing * (out.translations[root] - head);
    place_head();
  }
}

// 4. Arms: two-bone IK onto the controllers, elbows down, back and out; a
// lost hand hangs relaxed beside the body.
void Solver::arms() {
  const Quat chest_heading = yaw_rotation(st.chest_yaw);
  for (int s = 0; s < 2; ++s) {
    const auto su = idx(s);
    const double side = s == 0 ? 1.0 : -1.0;  // +x is the character's left
    const Vec3 shoulder = model[idx(M.arm_[s].root)].translation;
    TwoBoneTarget t;
    if (in.hand_valid[su]) {
      t.position = in.hand_position[su];
      t.rotation = in.hand_rotation[su];
      t.rotation_weight = 1.0;
    } else {
      t.position = shoulder + chest_heading * Vec3(side * 0.08, -0.95 * M.arm_length_, 0.05);
      t.rotation_weight = 0.0;
    }
    t.hint = 0.5 * (shoulder + t.position) + chest_heading * Vec3(side * 0.3, -0.5, -0.35);
    solve_two_bone(skel, M.arm_[s], t, out, model);
  }
}

// Each foot's place under the balance point.
std::array<Vec3, 2> Solver::foot_places(const Vec3& balance, double foot_y) const {
  std::array<Vec3, 2> place;
  for (int s = 0; s < 2; ++s) {
    Vec3 p = horizontal(balance) + yaw_rotation(st.pelvis_yaw) * M.foot_offset_[idx(s)];
    p.y() = foot_y;
    place[idx(s)] = p;
  }
  return place;
}

// Where a step started now would land: the foot's place when it lands, plus a lead.
Vec3 Solver::landing(const std::array<Vec3, 2>& place, int s, double remaining, double duration, double foot_y) const {
  Vec3 to = place[idx(s)] + st.velocity * (remaining + S.velocity_lead * 0.5 * duration);
  to.y() = foot_y;
  return to;
}

// Moves the stepping feet along their arcs; true while one is still in the air.
bool Solver::advance_steps(const std::array<Vec3, 2>& place, double foot_y) {
  bool any_stepping = false;
  for (int s = 0; s < 2; ++s) {
    auto& f = st.feet[idx(s)];
    if (!f.stepping) continue;
    f.step_time += dt;
    const double u = std::clamp(f.step_time / f.step_duration, 0.0, 1.0);
    Vec3 to = landing(place, s, f.step_duration - f.step_time, f.step_duration, foot_y);
    Vec3 stride = horizontal(to - f.from);
    if (stride.norm() > S.max_step_length) to = f.from + stride.normalized() * S.max_step_length;
    to.y() = foot_y;
    const double e = smoothstep(u);
    f.position = f.from + (to - f.from) * e;
    f.position.y() = foot_y + std::sin(kPi * u) * S.step_height;
    f.yaw = f.from_yaw + wrap_angle(st.pelvis_yaw - f.from_yaw) * e;
    if (u >= 1.0) {
      f.stepping = false;
      f.position = to;
      ++st.steps_taken;
    } else {
      any_stepping = true;
    }
  }
  return any_stepping;
}

// Starts a step of the foot that needs it most, if balance or placement asks.
void Solver::start_step(const std::array<Vec3, 2>& place, const Vec3& balance, double foot_y) {
  const bool off_balance = distance_to_segment(balance, st.feet[0].position, st.feet[1].position) > S.step_threshold;
  double worst = -1;
  int pick = -1;
  for (int s = 0; s < 2; ++s) {
    const auto& f = st.feet[idx(s)];
    const double away = horizontal(landing(place, s, 0.0, S.min_step_time, foot_y) - f.position).norm();
    const bool turned = std::abs(wrap_angle(st.pelvis_yaw - f.yaw)) > S.step_angle_threshold;
    const double score = away + (turned ? 1.0 : 0.0);
    if ((off_balance || away > S.foot_distance_threshold || turned) && score > worst) {
      worst = score;
      pick = s;
    }
  }
  if (pick < 0) return;
  auto& f = st.feet[idx(pick)];
  const double dist = horizontal(landing(place, pick, 0.0, S.min_step_time, foot_y) - f.position).norm();
  f.stepping = true;
  f.step_time = 0.0;
  // A swing foot moves about twice as fast as the body (it is still half the stride).
  const double speed = std::max(S.step_speed, S.swing_speed_ratio * st.velocity.norm());
  f.step_duration = std::clamp(dist / speed, S.min_step_time, S.max_step_time);
  f.from = f.position;
  f.from_yaw = f.yaw;
}

// 5. Feet: planted, stepping when balance or placement asks for it.
void Solver::locomotion() {
  const Vec3 pelvis = model[idx(M.pelvis_)].translation;
  const Vec3 head_now = in.head_position;
  if (!first && dt > 0) {
    const Vec3 v = horizontal(head_now - st.previous_head) / dt;
    st.velocity += (v - st.velocity) * (1.0 - std::exp(-dt / 0.1));
  } else {
    st.velocity.setZero();
  }
  st.previous_head = head_now;
  const double foot_y = S.floor_height + M.ankle_height_;
  // The balance point: mostly the head, which stays over the feet when the
  // hips go back in a crouch and leads in locomotion.
  const Vec3 balance = (1.0 - S.balance_head_weight) * pelvis + S.balance_head_weight * head_now;
  const std::array<Vec3, 2> place = foot_places(balance, foot_y);
  if (first) {
    for (int s = 0; s < 2; ++s) {
      auto& f = st.feet[idx(s)];
      f = State::Foot{};
      f.position = place[idx(s)];
      f.yaw = st.pelvis_yaw;
    }
    st.steps_taken = 0;
  }
  const bool any_stepping = advance_steps(place, foot_y);
  if (!any_stepping && !first) start_step(place, balance, foot_y);
}

// 6. Legs: two-bone IK onto the feet, knees toward the toes.
void Solver::legs() {
  for (int s = 0; s < 2; ++s) {
    const auto& f = st.feet[idx(s)];
    const Vec3 hip = model[idx(M.leg_[s].root)].translation;
    TwoBoneTarget t;
    t.position = f.position;
    t.rotation = yaw_rotation(f.yaw);
    t.rotation_weight = 1.0;
    const double knee_yaw = f.yaw + 0.5 * wrap_angle(st.pelvis_yaw - f.yaw);
    t.hint = 0.5 * (hip + f.position) + yaw_rotation(knee_yaw) * Vec3(0.0, 0.0, 0.6);
    solve_two_bone(skel, M.leg_[s], t, out, model);
  }
}

// Rest measurements: the standing body with straight legs under the hips.
void Solver::measure_rest(Model& m) {
  const Skeleton& skel = m.skel_;
  const std::vector<Vec3> rest = joint_positions(skel, Pose(skel));
  auto at = [&](int j) { return rest[idx(j)]; };
  const auto& leg = m.leg_;
  const auto& arm = m.arm_;
  m.leg_length_ = 0.5 * (bone(rest, leg[0].root, leg[0].mid) + bone(rest, leg[0].mid, leg[0].end) +
                         bone(rest, leg[1].root, leg[1].mid) + bone(rest, leg[1].mid, leg[1].end));
  m.arm_length_ = 0.5 * (bone(rest, arm[0].root, arm[0].mid) + bone(rest, arm[0].mid, arm[0].end) +
                         bone(rest, arm[1].root, arm[1].mid) + bone(rest, arm[1].mid, arm[1].end));
  // Ankle height above the sole: the foot's own vertical extent to its lowest point (toe).
  double sole = at(leg[0].end).y();
  if (skel.roles.has(Role::LeftToe)) {
    const int t = skel.roles[Role::LeftToe];
    sole = std::min(sole, at(t).y());
    if (skel.has_end_site[idx(t)]) sole = std::min(sole, at(t).y() + skel.end_sites[idx(t)].y());
  }
  // Never below 9% of the leg (a typical standing ankle height for adults).
  m.ankle_height_ = std::max(0.09 * 0.5 * (bone(rest, leg[0].root, leg[0].mid) + bone(rest, leg[0].mid, leg[0].end)),
                             at(leg[0].end).y() - sole);
  const double hip_below_pelvis = at(m.pelvis_).y() - 0.5 * (at(leg[0].root).y() + at(leg[1].root).y());
  // Standing knees are not locked straight: 2% shorter than the bones.
  m.pelvis_height_ = m.ankle_height_ + 0.98 * m.leg_length_ + hip_below_pelvis;
  m.torso_length_ = at(m.head_).y() - at(m.pelvis_).y();
  m.head_height_ = m.pelvis_height_ + m.torso_length_;
  for (int s = 0; s < 2; ++s) {
    Vec3 off = horizontal(at(leg[s].root) - at(m.pelvis_));
    off.x() += (s == 0 ? 0.02 : -0.02);  // feet a little wider than the hip joints
    off.z() = 0.0;
    m.foot_offset_[idx(s)] = off;
  }
}

Model make_model(const Skeleton& skel_in, const Settings& settings) {
  Model m;
  m.skel_ = skel_in;
  m.settings_ = settings;
  const Skeleton& skel = m.skel_;
  std::string missing;
  for (Role r : {Role::Pelvis, Role::Neck, Role::Head, Role::LeftShoulder, Role::LeftElbow, Role::LeftHand,
                 Role::RightShoulder, Role::RightElbow, Role::RightHand, Role::LeftHip, Role::LeftKnee,
                 Role::LeftAnkle, Role::RightHip, Role::RightKnee, Role::RightAnkle})
    if (!skel.roles.has(r)) missing += (missing.empty() ? "" : ", ") + std::string(role_name(r));
  if (!missing.empty()) throw Error("full-body IK: the skeleton has no joint for role(s) " + missing);

  m.arm_[0] = left_arm(skel);
  m.arm_[1] = right_arm(skel);
  m.leg_[0] = left_leg(skel);
  m.leg_[1] = right_leg(skel);
  m.pelvis_ = skel.roles[Role::Pelvis];
  m.head_ = skel.roles[Role::Head];
  m.clavicle_[0] = skel.roles[Role::LeftClavicle];
  m.clavicle_[1] = skel.roles[Role::RightClavicle];
  m.spine_ = skel.roles.spine_chain;
  const int neck = skel.roles[Role::Neck];
  for (int j = skel.parents[idx(m.head_)]; j >= 0; j = skel.parents[idx(j)]) {
    m.neck_.insert(m.neck_.begin(), j);
    if (j == neck) break;
  }
  if (m.neck_.empty() || m.neck_.front() != neck) throw Error("full-body IK: the neck joint is not an ancestor of the head");

  Solver::measure_rest(m);
  if (!(m.torso_length_ > 0.05) || !(m.leg_length_ > 0.1) || !(m.arm_length_ > 0.1))
    throw Error("full-body IK: the rest pose is not an upright body (torso " + std::to_string(m.torso_length_) +
                " m, leg " + std::to_string(m.leg_length_) + " m)");
  return m;
}

State::State(const Model& m) : scratch(static_cast<std::size_t>(m.skeleton().joint_count())) {}

void reset(const Model& model, State& st) {
  st.clock.reset();
  st.initialized = false;
  st.feet = {};
  st.chest_yaw = st.pelvis_yaw = 0;
  st.previous_head = st.velocity = Vec3::Zero();
  st.held_head = DevicePose{};
  st.steps_taken = 0;
  st.scratch.resize(static_cast<std::size_t>(model.skeleton().joint_count()));
}

namespace {

// The devices read through usable(): a lost head holds the last usable one
// (or stands at the origin before any), a lost hand relaxes its arm.
SolverInput read_devices(const Model& m, const TrackerFrame& frame, State& st) {
  SolverInput in;
  if (usable(frame.head())) st.held_head = frame.head();
  if (st.held_head.valid) {
    in.head_position = st.held_head.position;
    in.head_rotation = st.held_head.rotation.normalized();
  } else {
    in.head_position = Vec3(0.0, m.settings().floor_height + m.standing_head_height(), 0.0);
  }
  for (int s = 0; s < 2; ++s) {
    const DevicePose& hand = frame.hand(s);
    in.hand_valid[idx(s)] = usable(hand);
    if (!in.hand_valid[idx(s)]) continue;
    in.hand_position[idx(s)] = hand.position;
    in.hand_rotation[idx(s)] = hand.rotation;
  }
  return in;
}

}  // namespace

UpdateStatus update(const Model& M, const TrackerFrame& frame, State& st, PoseRef out, Info* info) {
  if (out.joint_count() != M.skeleton().joint_count() || st.scratch.size() != out.rotations.size())
    return UpdateStatus::Rejected;  // a pose or state of another model
  const FrameClock::Step step = st.clock.advance(frame.time);
  if (step.verdict == FrameClock::Verdict::Reject) return UpdateStatus::Rejected;
  if (step.verdict == FrameClock::Verdict::Restart) st.initialized = false;  // a new start: feet re-placed
  const SolverInput in = read_devices(M, frame, st);
  const bool first = !st.initialized;
  Solver solver{M, M.settings(), M.skeleton(), in, st, out, std::span<Transform>(st.scratch), first, first ? 0.0 : std::max(step.dt, 0.0)};
  solver.headings();
  const double lean = solver.crouch_lean();
  solver.torso(lean);
  solver.clavicles();
  solver.swing_body();
  solver.arms();
  solver.locomotion();
  solver.legs();
  // Until a usable head has been seen the body stands at the origin and
  // starts afresh on every frame.
  st.initialized = st.held_head.valid;

  const bool head_ok = usable(frame.head());
  if (info) {
    info->steps_taken = st.steps_taken;
    info->stepping = {st.feet[0].stepping, st.feet[1].stepping};
    info->chest_yaw = st.chest_yaw;
    info->pelvis_yaw = st.pelvis_yaw;
    info->lean = lean;
    info->head_tracked = head_ok;
    info->hand_tracked = in.hand_valid;
  }
  if (step.verdict == FrameClock::Verdict::Restart) return UpdateStatus::Restarted;
  return head_ok && in.hand_valid[0] && in.hand_valid[1] ? UpdateStatus::Ok : UpdateStatus::Degraded;
}

void describe(const Info& i, InfoFields& out) {
  out.add("steps", i.steps_taken);
  out.add("lean", i.lean);
  out.add("head_tracked", i.head_tracked ? 1.0 : 0.0);
}

}  // namespace legwork::ik
