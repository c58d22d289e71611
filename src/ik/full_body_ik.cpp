// VRIK-style full-body IK from head + two hands (see full_body.hpp).
#include <legwork/ik/full_body.hpp>

#include <legwork/core/fk.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace legwork::ik {
namespace {

Quat yaw_rotation(double yaw) { return Quat(Eigen::AngleAxisd(yaw, Vec3::UnitY())); }
Quat pitch_rotation(double pitch) { return Quat(Eigen::AngleAxisd(pitch, Vec3::UnitX())); }
// Wraps an angle to (-pi, pi].
double wrap(double a) { return std::remainder(a, 2.0 * kPi); }
// Heading of a direction about y (0 = facing +z), or `fallback` if it is vertical.
double heading_of(const Vec3& dir, double fallback) {
  if (dir.x() * dir.x() + dir.z() * dir.z() < 1e-8) return fallback;
  return std::atan2(dir.x(), dir.z());
}
Vec3 horizontal(const Vec3& v) { return {v.x(), 0.0, v.z()}; }

// Horizontal distance from p to the segment [a, b].
double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ph = horizontal(p), ah = horizontal(a), bh = horizontal(b);
  const Vec3 ab = bh - ah;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 1e-12 ? std::clamp((ph - ah).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (ph - (ah + t * ab)).norm();
}

double smoothstep(double u) { return u * u * (3.0 - 2.0 * u); }

Quat parent_model_rotation(const Skeleton& skel, std::span<const Transform> model, int j) {
  const int p = skel.parents[static_cast<std::size_t>(j)];
  return p < 0 ? Quat::Identity() : model[static_cast<std::size_t>(p)].rotation;
}

double bone(const std::vector<Vec3>& rest, int a, int b) {
  return (rest[static_cast<std::size_t>(a)] - rest[static_cast<std::size_t>(b)]).norm();
}

}  // namespace

FullBodyModel::FullBodyModel(const Skeleton& skel, const FullBodySettings& settings) : skel_(&skel), settings_(settings) {
  std::string missing;
  for (Role r : {Role::Pelvis, Role::Neck, Role::Head, Role::LeftShoulder, Role::LeftElbow, Role::LeftHand,
                 Role::RightShoulder, Role::RightElbow, Role::RightHand, Role::LeftHip, Role::LeftKnee,
                 Role::LeftAnkle, Role::RightHip, Role::RightKnee, Role::RightAnkle})
    if (!skel.roles.has(r)) missing += (missing.empty() ? "" : ", ") + std::string(role_name(r));
  if (!missing.empty()) throw Error("full-body IK: the skeleton has no joint for role(s) " + missing);

  arm_[0] = left_arm(skel);
  arm_[1] = right_arm(skel);
  leg_[0] = left_leg(skel);
  leg_[1] = right_leg(skel);
  pelvis_ = skel.roles[Role::Pelvis];
  head_ = skel.roles[Role::Head];
  clavicle_[0] = skel.roles[Role::LeftClavicle];
  clavicle_[1] = skel.roles[Role::RightClavicle];
  spine_ = skel.roles.spine_chain;
  const int neck = skel.roles[Role::Neck];
  for (int j = skel.parents[static_cast<std::size_t>(head_)]; j >= 0; j = skel.parents[static_cast<std::size_t>(j)]) {
    neck_.insert(neck_.begin(), j);
    if (j == neck) break;
  }
  if (neck_.empty() || neck_.front() != neck) throw Error("full-body IK: the neck joint is not an ancestor of the head");

  // Rest measurements: the standing body with straight legs under the hips.
  const std::vector<Vec3> rest = joint_positions(skel, Pose(skel));
  auto at = [&](int j) { return rest[static_cast<std::size_t>(j)]; };
  leg_length_ = 0.5 * (bone(rest, leg_[0].root, leg_[0].mid) + bone(rest, leg_[0].mid, leg_[0].end) +
                       bone(rest, leg_[1].root, leg_[1].mid) + bone(rest, leg_[1].mid, leg_[1].end));
  arm_length_ = 0.5 * (bone(rest, arm_[0].root, arm_[0].mid) + bone(rest, arm_[0].mid, arm_[0].end) +
                       bone(rest, arm_[1].root, arm_[1].mid) + bone(rest, arm_[1].mid, arm_[1].end));
  // Ankle height above the sole: the foot's own vertical extent to its lowest point (toe).
  double sole = at(leg_[0].end).y();
  for (Role toe : {Role::LeftToe})
    if (skel.roles.has(toe)) {
      const int t = skel.roles[toe];
      sole = std::min(sole, at(t).y());
      if (skel.has_end_site[static_cast<std::size_t>(t)]) sole = std::min(sole, at(t).y() + skel.end_sites[static_cast<std::size_t>(t)].y());
    }
  // Never below 9% of the leg (a typical standing ankle height for adults).
  ankle_height_ = std::max(0.09 * 0.5 * (bone(rest, leg_[0].root, leg_[0].mid) + bone(rest, leg_[0].mid, leg_[0].end)), at(leg_[0].end).y() - sole);
  const double hip_below_pelvis = at(pelvis_).y() - 0.5 * (at(leg_[0].root).y() + at(leg_[1].root).y());
  // Standing knees are not locked straight: 2% shorter than the bones.
  pelvis_height_ = ankle_height_ + 0.98 * leg_length_ + hip_below_pelvis;
  torso_length_ = at(head_).y() - at(pelvis_).y();
  head_height_ = pelvis_height_ + torso_length_;
  for (int s = 0; s < 2; ++s) {
    Vec3 off = horizontal(at(leg_[s].root) - at(pelvis_));
    off.x() += (s == 0 ? 0.02 : -0.02);  // feet a little wider than the hip joints
    off.z() = 0.0;
    foot_offset_[static_cast<std::size_t>(s)] = off;
  }
  if (!(torso_length_ > 0.05) || !(leg_length_ > 0.1) || !(arm_length_ > 0.1))
    throw Error("full-body IK: the rest pose is not an upright body (torso " + std::to_string(torso_length_) +
                " m, leg " + std::to_string(leg_length_) + " m)");
}

FullBodyState::FullBodyState(const FullBodyModel& m) : model(static_cast<std::size_t>(m.skeleton().joint_count())) {}

void solve_full_body(const FullBodyModel& M, const TrackerFrame& input, double dt, FullBodyState& st, PoseRef out) {
  // Bad samples: without a usable head the pose is left as it was; a hand
  // with non-finite data is treated as lost tracking (that arm relaxes).
  const auto finite = [](const auto& v) { return v.allFinite(); };
  if (!finite(input.head_position) || !finite(input.head_rotation.coeffs()) ||
      input.head_rotation.squaredNorm() < 1e-12 || !std::isfinite(dt))
    return;
  TrackerFrame in = input;
  in.head_rotation.normalize();
  for (std::size_t s = 0; s < 2; ++s)
    if (!finite(in.hand_position[s]) || !finite(in.hand_rotation[s].coeffs()) || in.hand_rotation[s].squaredNorm() < 1e-12)
      in.hand_valid[s] = false;
  const Skeleton& skel = *M.skel_;
  const FullBodySettings& S = M.settings_;
  const std::span<Transform> model(st.model);
  const bool first = !st.initialized;
  dt = first ? 0.0 : std::max(dt, 0.0);

  // 1. Headings: chest between head and hands, pelvis following the chest.
  const double head_yaw = heading_of(in.head_rotation * Vec3::UnitZ(), first ? 0.0 : st.chest_yaw);
  double chest_yaw = head_yaw;
  if (in.hand_valid[0] && in.hand_valid[1]) {
    const Vec3 across = horizontal(in.hand_position[0] - in.hand_position[1]);  // right -> left
    const double hands_yaw = heading_of(across.cross(Vec3::UnitY()), head_yaw);
    const double d = wrap(hands_yaw - head_yaw);
    // Crossed hands (|d| > 90 degrees) say nothing about the body's heading.
    if (std::abs(d) < 0.5 * kPi) chest_yaw = head_yaw + S.hands_heading_weight * std::clamp(across.norm() / 0.3, 0.0, 1.0) * d;
  }
  if (first) st.pelvis_yaw = chest_yaw;
  else st.pelvis_yaw += wrap(chest_yaw - st.pelvis_yaw) * (1.0 - std::exp(-S.pelvis_turn_rate * dt));
  const double max_twist = 0.6;
  st.pelvis_yaw = chest_yaw - std::clamp(wrap(chest_yaw - st.pelvis_yaw), -max_twist, max_twist);
  st.chest_yaw = chest_yaw;

  // 2. Crouch and lean: the legs take most of a head drop down to the lowest
  // pelvis height; the rest (and anything beyond) is a forward lean.
  const double head_h = in.head_position.y() - S.floor_height;
  const double drop = std::max(0.0, M.head_height_ - head_h);
  const double min_pelvis = S.min_pelvis_fraction * M.pelvis_height_;
  double pelvis_h = std::max(min_pelvis, M.pelvis_height_ - S.crouch_leg_share * drop);
  if (head_h - pelvis_h > M.torso_length_) pelvis_h = head_h - M.torso_length_;
  const double lean = std::acos(std::clamp((head_h - pelvis_h) / M.torso_length_, 0.0, 1.0));

  // 3. Torso rotations (rest elsewhere), then the neck shares the head's turn.
  for (int j = 0; j < out.joint_count(); ++j) {
    out.rotations[static_cast<std::size_t>(j)] = Quat::Identity();
    out.translations[static_cast<std::size_t>(j)] = skel.rest_offsets[static_cast<std::size_t>(j)];
  }
  const auto root = static_cast<std::size_t>(M.pelvis_);
  const double twist = wrap(st.chest_yaw - st.pelvis_yaw);
  const double n_spine = static_cast<double>(std::max<std::size_t>(M.spine_.size(), 1));
  const double hip_lean = M.spine_.empty() ? lean : S.pelvis_lean_share * lean;
  out.rotations[root] = yaw_rotation(st.pelvis_yaw) * pitch_rotation(hip_lean);
  if (M.spine_.empty()) out.rotations[root] = yaw_rotation(st.chest_yaw) * pitch_rotation(lean);
  for (int j : M.spine_)
    out.rotations[static_cast<std::size_t>(j)] = yaw_rotation(twist / n_spine) * pitch_rotation((lean - hip_lean) / n_spine);
  out.translations[root] = Vec3::Zero();
  // The neck takes a share of the head's turn relative to the chest; then the
  // body is placed so the head joint is exactly on the headset.
  const auto place_head = [&] {
    forward_kinematics(skel, out, model);
    const Quat chest = parent_model_rotation(skel, model, M.neck_.front());
    Quat delta = chest.conjugate() * in.head_rotation.normalized();
    if (delta.w() < 0) delta.coeffs() = -delta.coeffs();
    // Powers of one rotation compose exactly: the head ends on the headset's orientation.
    const double neck_part = S.neck_share / static_cast<double>(M.neck_.size());
    for (int j : M.neck_) out.rotations[static_cast<std::size_t>(j)] = Quat::Identity().slerp(neck_part, delta);
    out.rotations[static_cast<std::size_t>(M.head_)] = Quat::Identity().slerp(1.0 - S.neck_share, delta);
    forward_kinematics(skel, out, model);
    const Vec3 shift = in.head_position - model[static_cast<std::size_t>(M.head_)].translation;
    out.translations[root] += shift;
    for (auto& t : model) t.translation += shift;
  };
  place_head();

  // Clavicles help long reaches.
  for (int s = 0; s < 2; ++s) {
    const int c = M.clavicle_[s];
    if (c < 0 || !in.hand_valid[static_cast<std::size_t>(s)]) continue;
    const Vec3 shoulder = model[static_cast<std::size_t>(M.arm_[s].root)].translation;
    const Vec3 target = in.hand_position[static_cast<std::size_t>(s)];
    // Swing the clavicle just enough to bring the shoulder within reach, up to a limit.
    const double excess = (target - shoulder).norm() - 0.995 * M.arm_length_;
    if (excess <= 0) continue;
    const Vec3 cp = model[static_cast<std::size_t>(c)].translation;
    const Vec3 bone = shoulder - cp;
    const double len = bone.norm();
    const Vec3 axis = bone.cross(target - cp);
    if (len < 1e-6 || axis.norm() < 1e-9) continue;
    const double angle = std::min(S.clavicle_reach, 1.2 * excess / len);
    const Quat cm = (Quat(Eigen::AngleAxisd(angle, axis.normalized())) * model[static_cast<std::size_t>(c)].rotation).normalized();
    out.rotations[static_cast<std::size_t>(c)] = (parent_model_rotation(skel, model, c).conjugate() * cm).normalized();
  }
  forward_kinematics(skel, out, model);
  // Still out of reach (arms stretched overhead while lying, a long reach):
  // swing the whole body about the head toward that hand, so the head stays
  // on the headset and the hands stay exact.
  for (int iter = 0; iter < 4; ++iter) {
    double worst = 0;
    int side = -1;
    for (int s = 0; s < 2; ++s) {
      if (!in.hand_valid[static_cast<std::size_t>(s)]) continue;
      const double e = (in.hand_position[static_cast<std::size_t>(s)] -
                        model[static_cast<std::size_t>(M.arm_[s].root)].translation).norm() - 0.999 * M.arm_length_;
      if (e > worst) {
        worst = e;
        side = s;
      }
    }
    if (side < 0) break;
    const Vec3 head = model[static_cast<std::size_t>(M.head_)].translation;
    const Vec3 arm = model[static_cast<std::size_t>(M.arm_[side].root)].translation - head;
    const Vec3 axis = arm.cross(in.hand_position[static_cast<std::size_t>(side)] - head);
    if (arm.norm() < 1e-6 || axis.norm() < 1e-9) break;
    const Quat swing(Eigen::AngleAxisd(std::min(S.body_reach, 1.1 * worst / arm.norm()), axis.normalized()));
    out.rotations[root] = (swing * out.rotations[root]).normalized();
    out.translations[root] = head + swing * (out.translations[root] - head);
    place_head();
  }

  // 4. Arms: two-bone IK onto the controllers, elbows down, back and out.
  const Quat chest_heading = yaw_rotation(st.chest_yaw);
  for (int s = 0; s < 2; ++s) {
    const auto su = static_cast<std::size_t>(s);
    const double side = s == 0 ? 1.0 : -1.0;  // +x is the character's left
    const Vec3 shoulder = model[static_cast<std::size_t>(M.arm_[s].root)].translation;
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

  // 5. Feet: planted, stepping when balance or placement asks for it.
  const Vec3 pelvis = model[root].translation;
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
  std::array<Vec3, 2> place;
  for (int s = 0; s < 2; ++s) {
    Vec3 p = horizontal(balance) + yaw_rotation(st.pelvis_yaw) * M.foot_offset_[static_cast<std::size_t>(s)];
    p.y() = foot_y;
    place[static_cast<std::size_t>(s)] = p;
  }
  if (first) {
    for (int s = 0; s < 2; ++s) {
      auto& f = st.feet[static_cast<std::size_t>(s)];
      f = FullBodyState::Foot{};
      f.position = place[static_cast<std::size_t>(s)];
      f.yaw = st.pelvis_yaw;
    }
    st.steps_taken = 0;
  }
  // Where a step started now would land: the foot's place when it lands, plus a lead.
  auto landing = [&](int s, double remaining, double duration) {
    Vec3 to = place[static_cast<std::size_t>(s)] + st.velocity * (remaining + S.velocity_lead * 0.5 * duration);
    to.y() = foot_y;
    return to;
  };
  bool any_stepping = false;
  for (int s = 0; s < 2; ++s) {
    auto& f = st.feet[static_cast<std::size_t>(s)];
    if (!f.stepping) continue;
    f.step_time += dt;
    const double u = std::clamp(f.step_time / f.step_duration, 0.0, 1.0);
    Vec3 to = landing(s, f.step_duration - f.step_time, f.step_duration);
    Vec3 stride = horizontal(to - f.from);
    if (stride.norm() > S.max_step_length) to = f.from + stride.normalized() * S.max_step_length;
    to.y() = foot_y;
    const double e = smoothstep(u);
    f.position = f.from + (to - f.from) * e;
    f.position.y() = foot_y + std::sin(kPi * u) * S.step_height;
    f.yaw = f.from_yaw + wrap(st.pelvis_yaw - f.from_yaw) * e;
    if (u >= 1.0) {
      f.stepping = false;
      f.position = to;
      ++st.steps_taken;
    } else {
      any_stepping = true;
    }
  }
  if (!any_stepping && !first) {
    const bool off_balance =
        distance_to_segment(balance, st.feet[0].position, st.feet[1].position) > S.step_threshold;
    double worst = -1;
    int pick = -1;
    for (int s = 0; s < 2; ++s) {
      const auto& f = st.feet[static_cast<std::size_t>(s)];
      const double away = horizontal(landing(s, 0.0, S.min_step_time) - f.position).norm();
      const bool turned = std::abs(wrap(st.pelvis_yaw - f.yaw)) > S.step_angle_threshold;
      const double score = away + (turned ? 1.0 : 0.0);
      if ((off_balance || away > S.foot_distance_threshold || turned) && score > worst) {
        worst = score;
        pick = s;
      }
    }
    if (pick >= 0) {
      auto& f = st.feet[static_cast<std::size_t>(pick)];
      const double dist = horizontal(landing(pick, 0.0, S.min_step_time) - f.position).norm();
      f.stepping = true;
      f.step_time = 0.0;
      // A swing foot moves about twice as fast as the body (it is still half the stride).
      const double speed = std::max(S.step_speed, S.swing_speed_ratio * st.velocity.norm());
      f.step_duration = std::clamp(dist / speed, S.min_step_time, S.max_step_time);
      f.from = f.position;
      f.from_yaw = f.yaw;
    }
  }

  // 6. Legs: two-bone IK onto the feet, knees toward the toes.
  for (int s = 0; s < 2; ++s) {
    const auto& f = st.feet[static_cast<std::size_t>(s)];
    const Vec3 hip = model[static_cast<std::size_t>(M.leg_[s].root)].translation;
    TwoBoneTarget t;
    t.position = f.position;
    t.rotation = yaw_rotation(f.yaw);
    t.rotation_weight = 1.0;
    const double knee_yaw = f.yaw + 0.5 * wrap(st.pelvis_yaw - f.yaw);
    t.hint = 0.5 * (hip + f.position) + yaw_rotation(knee_yaw) * Vec3(0.0, 0.0, 0.6);
    solve_two_bone(skel, M.leg_[s], t, out, model);
  }
  st.initialized = true;
}

}  // namespace legwork::ik
