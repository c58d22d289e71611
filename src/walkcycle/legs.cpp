// The smooth root's legs (see legs.hpp).
#include <legwork/walkcycle/legs.hpp>

#include <legwork/core/rotation.hpp>

#include <cmath>

namespace legwork::walkcycle {

LegJoints leg_joints(const CycleModel& m) {
  LegJoints l;
  for (const FootPivots* f : {&m.right, &m.left}) {
    for (int i = 0; i < f->chain_length && l.count + 1 < static_cast<int>(l.joints.size()); ++i)
      l.joints[static_cast<std::size_t>(l.count++)] = f->chain[static_cast<std::size_t>(i)];
    if (f->toe >= 0) {
      if (m.skeleton.parents[static_cast<std::size_t>(f->toe)] != f->ankle) l.all = true;
      l.joints[static_cast<std::size_t>(l.count++)] = f->toe;
    }
  }
  if (l.all) l.count = 0;
  return l;
}

void leg_kinematics(const Skeleton& s, const LegJoints& legs, ConstPoseRef pose, std::span<Transform> g) {
  if (legs.all) return forward_kinematics(s, pose, g);
  for (int j : legs.list()) {
    const auto u = static_cast<std::size_t>(j);
    const int p = s.parents[u];
    if (p < 0) {
      g[u] = {pose.rotations[u], pose.translations[u]};
    } else {
      const Transform& gp = g[static_cast<std::size_t>(p)];
      g[u].rotation = gp.rotation * pose.rotations[u];
      g[u].translation = gp.rotation * pose.translations[u] + gp.translation;
    }
  }
}

void shift_legs(const LegJoints& legs, std::span<const Transform> before, const Vec3& shift, std::span<Transform> g) {
  auto move = [&](std::size_t j) { g[j] = {before[j].rotation, before[j].translation + shift}; };
  if (legs.all)
    for (std::size_t j = 0; j < g.size(); ++j) move(j);
  else
    for (int j : legs.list()) move(static_cast<std::size_t>(j));
}

LegIk leg_of(const Skeleton& s, bool left, std::span<const Transform> g) {
  LegIk leg{left ? ik::left_leg(s) : ik::right_leg(s), 0.0};
  auto pos = [&](int j) { return g[static_cast<std::size_t>(j)].translation; };
  leg.length = (pos(leg.chain.mid) - pos(leg.chain.root)).norm() + (pos(leg.chain.end) - pos(leg.chain.mid)).norm();
  return leg;
}

double soften_reach(const Vec3& hip, const LegIk& leg, double soft, Vec3& target) {
  const Vec3 d = target - hip;
  const double dist = d.norm(), start = soft * leg.length, room = leg.length - start;
  if (dist > start && room > 0) {
    const double reached = start + room * (1.0 - std::exp(-(dist - start) / room));
    target = hip + d * (reached / dist);
  }
  return leg.length > 0 ? dist / leg.length : 0.0;
}

// Rolling by a about the side axis k through the pivot P takes the ankle to
// P + R(a) v (v = ankle - P), whose squared distance from the hip H is
// C + A cos a + B sin a = C + M cos(a - phi) with u = P - H,
// A = 2 u.v_perp, B = 2 u.(k x v), C = |u|^2 + |v|^2 + 2 u.v_par: solved in
// closed form.
double roll_foot(const FootPivots& foot, const Vec3& hip, double reach, const Vec3& forward, const Pivot* stance,
                 Transform& ankle) {
  const Vec3 to_ankle = ankle.translation - hip;
  if (!(to_ankle.norm() > reach) || (stance && *stance == Pivot::Heel)) return 0.0;
  const bool on_ball = stance || to_ankle.dot(forward) < 0;
  const Vec3 pivot = ankle.apply(on_ball ? foot.ball_local : foot.heel_local);
  const Vec3 k = Vec3::UnitY().cross(forward).normalized();  // the foot's side axis
  const Vec3 u = pivot - hip, v = ankle.translation - pivot;
  const Vec3 v_par = k.dot(v) * k, v_perp = v - v_par;
  const double A = 2 * u.dot(v_perp), B = 2 * u.dot(k.cross(v)), C = u.squaredNorm() + v.squaredNorm() + 2 * u.dot(v_par);
  const double M = std::hypot(A, B), phi = std::atan2(B, A), limit = deg2rad(60.0);
  auto wrap = [](double a) { return std::remainder(a, 2 * kPi); };
  auto f = [&](double a) { return C + M * std::cos(a - phi); };
  double angle = 0;
  const double c = M > 1e-15 ? (reach * reach - C) / M : -2.0;
  if (c >= -1.0) {  // within reach on the arc of angles around phi + pi; the nearest edge of it
    const double a1 = wrap(phi + std::acos(std::min(c, 1.0))), a2 = wrap(phi - std::acos(std::min(c, 1.0)));
    angle = std::abs(a1) < std::abs(a2) ? a1 : a2;
  }
  if (c < -1.0 || std::abs(angle) > limit) {  // out of reach: the closest within the limits
    angle = std::clamp(wrap(phi + kPi), -limit, limit);
    if (std::abs(wrap(phi + kPi)) > limit) angle = f(limit) < f(-limit) ? limit : -limit;
  }
  const Quat q(Eigen::AngleAxisd(angle, k));
  ankle.translation = pivot + q * v;
  ankle.rotation = (q * ankle.rotation).normalized();
  return angle;
}

double drop_to_reach(const Vec3& hip, const Vec3& target, double reach) {
  const double side = horizontal(target - hip).norm(), above = hip.y() - target.y();
  if (side >= reach) return std::max(0.0, above);
  return std::max(0.0, above - std::sqrt(reach * reach - side * side));
}

const FootHold& StanceTurn::advance(const Frame& in) {
  if (!started) heel = in.heel, ball = in.ball, started = true;
  const double rise = 0.02;  // metres of heel lift over which the foot turns on its ball
  const double yaw = std::atan2(in.ball.x() - in.heel.x(), in.ball.z() - in.heel.z());
  if (in.stance) {
    const bool landing = !stance;
    if (landing) landed_yaw = yaw, turned = 0;
    // Its pivot: the heel, then the ball from the pass key or as soon as
    // the heel is up with the ball down (a foot rising early to its toes).
    const bool heel_up = in.heel.y() > kFootDownTolerance && in.ball.y() <= kFootDownTolerance;
    const Pivot pv = (!landing && pivot == Pivot::Ball) || in.pivot == Pivot::Ball || heel_up ? Pivot::Ball : Pivot::Heel;
    if (landing || pv != pivot) anchor = horizontal(hold.apply(pv == Pivot::Heel ? heel : ball));
    pivot = pv;
    const Vec3& now = pv == Pivot::Heel ? in.heel : in.ball;
    hold.pivot = now;
    hold.offset = anchor - horizontal(now);  // the pivot stays where it was, wherever the plan has it
    if (pv == Pivot::Ball) {
      turned = std::max(turned, smoothstep((in.heel.y() - kFootDownTolerance) / rise));
      if (!in.stopping) turned = std::max(turned, smoothstep((in.step_fraction - 0.75) / 0.25));
    }
    hold.angle = std::remainder(landed_yaw - yaw, 2 * kPi) * (1.0 - turned);
    hold.on_ball = pv == Pivot::Ball;
  } else {
    if (stance) left_ground = in.time, lift_off = horizontal(hold.apply(heel) - heel);
    const double u = left_ground < 0 ? 1.0 : ((in.time - left_ground) / in.step_time - 0.25) / 0.6;
    hold = {0.0, Vec3::Zero(), lift_off * (1 - smoothstep(u))};
    pivot = Pivot::Heel;
  }
  stance = in.stance, heel = in.heel, ball = in.ball;
  return hold;
}

void update_toe(const Skeleton& s, const FootPivots& foot, ConstPoseRef pose, std::span<Transform> g) {
  if (foot.toe < 0) return;
  const auto t = static_cast<std::size_t>(foot.toe);
  if (s.parents[t] != foot.ankle) return forward_kinematics(s, pose, g);
  g[t] = g[static_cast<std::size_t>(foot.ankle)] * Transform{pose.rotations[t], pose.translations[t]};
}

LegPlacement place_leg(const LegFrame& frame, const LegIk& leg, const FootPivots& foot, const FootHold& hold,
                       const Pivot* pivot, bool apply, PoseRef pose, std::span<Transform> g) {
  const Skeleton& sk = frame.skeleton;
  const Ground& ground = frame.ground;
  const auto end = static_cast<std::size_t>(leg.chain.end);
  const Vec3 hip = g[static_cast<std::size_t>(leg.chain.root)].translation;
  Transform ankle = hold.apply(frame.before[end]);
  const double keyed =
      (frame.before[end].translation - frame.before[static_cast<std::size_t>(leg.chain.root)].translation).norm() / leg.length;
  const double soft = std::max(frame.soft_reach, keyed);
  LegPlacement out;
  Quat slope;  // the ground's turn under the foot (its toes follow it)
  fit_to_ground(ground, foot, pivot && (*pivot == Pivot::Ball || hold.on_ball), ankle, slope);
  out.roll = roll_foot(foot, hip, soft * leg.length, frame.forward, pivot, ankle);
  out.drop = drop_to_reach(hip, ankle.translation, soft * leg.length);
  ik::TwoBoneTarget t;
  t.position = ankle.translation;
  t.rotation = ankle.rotation;
  t.rotation_weight = 1.0;
  t.hint = frame.before[static_cast<std::size_t>(leg.chain.mid)].translation + frame.shift;
  out.reach = soften_reach(hip, leg, soft, t.position);
  out.limited = out.reach > soft + 1e-6;
  if (!apply) return out;
  auto solve_leg = [&] {
    ik::solve_two_bone(sk, leg.chain, t, pose, g);
    if ((out.roll != 0.0 || !ground.flat()) && foot.toe >= 0)
      pose.rotations[static_cast<std::size_t>(foot.toe)] =
          (t.rotation.conjugate() * slope * yaw_rotation(hold.angle) * frame.before[static_cast<std::size_t>(foot.toe)].rotation)
              .normalized();
    update_toe(sk, foot, pose, g);
  };
  solve_leg();
  out.lift = depth_below(sk, foot, std::span<const Transform>(g), [&](const Vec3& p) { return ground.height(p); });
  if (out.lift > 0) {
    t.position.y() += out.lift;
    solve_leg();
  }
  return out;
}

}  // namespace legwork::walkcycle
