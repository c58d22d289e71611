// Smooth root motion with the feet held by leg IK (see root_motion.hpp).
#include "root_motion.hpp"

#include <legwork/walkcycle/legs.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/rotation.hpp>
#include <legwork/ik/two_bone.hpp>
#include <legwork/walkcycle/offline/measure.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace legwork::walkcycle {

namespace {

// The series as a function of real frame x: linear between frames, straight
// lines at the end velocities beyond the ends.
struct Extended {
  std::span<const Vec3> q;
  Vec3 v_first = Vec3::Zero(), v_last = Vec3::Zero();
  Extended(std::span<const Vec3> series, double width, bool rest_at_end) : q(series) {
    const double last = static_cast<double>(q.size()) - 1;
    const double w = std::min(width, last);
    if (w > 0) {
      v_first = (at(w) - q.front()) / w;
      if (!rest_at_end) v_last = (q.back() - at(last - w)) / w;
    }
  }
  Vec3 at(double x) const {
    const double last = static_cast<double>(q.size()) - 1;
    if (x <= 0) return q.front() + x * v_first;
    if (x >= last) return q.back() + (x - last) * v_last;
    const auto i = static_cast<std::size_t>(x);
    const double u = x - static_cast<double>(i);
    return (1 - u) * q[i] + u * q[i + 1];
  }
  // Exact integral over [a, b] (trapezoids between whole frames); `whole`:
  // at(k) of the whole frames k from `first` on, and `piece`: the trapezoid
  // from k - 1 to k, computed once for every window (the same values).
  Vec3 integral(double a, double b, std::span<const Vec3> whole, std::span<const Vec3> piece, double first) const {
    Vec3 sum = Vec3::Zero();
    double x = a;
    Vec3 fx = at(a);
    const auto size = static_cast<std::ptrdiff_t>(whole.size());
    double k = std::floor(x) + 1.0;  // (= floor(x) + 1 each time)
    for (auto i = static_cast<std::ptrdiff_t>(k - first); x < b; k += 1.0, ++i) {
      const double next = std::min(b, k);
      const bool cached = next == k && i >= 1 && i < size;
      if (cached && x == k - 1.0) {
        sum += piece[static_cast<std::size_t>(i)];
        fx = whole[static_cast<std::size_t>(i)];
      } else {
        const Vec3 fn = cached ? whole[static_cast<std::size_t>(i)] : at(next);
        sum += 0.5 * (next - x) * (fx + fn);
        fx = fn;
      }
      x = next;
    }
    return sum;
  }
};

}  // namespace

std::vector<Vec3> window_average(std::span<const Vec3> q, double width, bool rest_at_end) {
  std::vector<Vec3> out(q.begin(), q.end());
  if (q.size() < 2 || !(width > 0)) return out;
  const Extended e(q, width, rest_at_end);
  // The windows reach whole frames first ... last; their values (extended beyond the ends) once.
  const double first = std::floor(-0.5 * width), last = std::ceil(static_cast<double>(q.size()) - 1 + 0.5 * width);
  std::vector<Vec3> whole(static_cast<std::size_t>(last - first) + 1);
  std::vector<Vec3> piece(whole.size(), Vec3::Zero());
  for (std::size_t i = 0; i < whole.size(); ++i) whole[i] = e.at(first + static_cast<double>(i));
  for (std::size_t i = 1; i < whole.size(); ++i) piece[i] = 0.5 * 1.0 * (whole[i - 1] + whole[i]);
  for (std::size_t f = 0; f < q.size(); ++f) {
    const double x = static_cast<double>(f);
    out[f] = e.integral(x - 0.5 * width, x + 0.5 * width, whole, piece, first) / width;
  }
  return out;
}

namespace {

// How far through its step each frame is (0 at the step's first frame, 1 at its last).
std::vector<double> step_fractions(std::span<const FrameLabel> labels) {
  std::vector<double> frac(labels.size(), 0.0);
  std::size_t begin = 0;
  for (std::size_t f = 1; f <= labels.size(); ++f) {
    if (f < labels.size() && labels[f].step == labels[begin].step) continue;
    const double span = static_cast<double>(f - 1 - begin);
    for (std::size_t k = begin; k < f; ++k) frac[k] = span > 0 ? static_cast<double>(k - begin) / span : 1.0;
    begin = f;
  }
  return frac;
}

// Each stance foot turns on its ball, not in place (StanceTurn, legs.hpp):
// both feet's turns fed frame by frame, in order, from the plan's FK.
struct StanceTurns {
  StanceTurns(const CycleModel& model, std::span<const FrameLabel> labels, double step)
      : m(model), frac(step_fractions(labels)), step_frames(step) {}
  // The holds of frame f (`g`: the FK of the plan's frame f, the legs' joints at least).
  std::array<FootHold, 2> at(int f, std::span<const Transform> g, const FrameLabel& l) {
    std::array<FootHold, 2> out;
    for (int side = 0; side < 2; ++side) {
      const FootPivots& foot = m.foot(side == 1);
      const Transform& ankle = g[static_cast<std::size_t>(foot.ankle)];
      StanceTurn::Frame in;
      in.heel = ankle.apply(foot.heel_local), in.ball = ankle.apply(foot.ball_local);
      in.stance = l.left_stance == (side == 1);
      in.pivot = l.pivot;
      in.step_fraction = frac[static_cast<std::size_t>(f)];
      in.stopping = l.stopping;
      in.time = f, in.step_time = step_frames;
      out[static_cast<std::size_t>(side)] = sides[side].advance(in);
    }
    return out;
  }
  const CycleModel& m;
  std::vector<double> frac;
  double step_frames;
  StanceTurn sides[2];
};

// Per frame, per side (0 = right, 1 = left).
std::vector<std::array<FootHold, 2>> hold_stance_yaw(const CycleModel& m, const Motion& plan,
                                                     std::span<const FrameLabel> labels, double step_frames) {
  const int n = std::min(plan.frame_count(), static_cast<int>(labels.size()));
  std::vector<std::array<FootHold, 2>> holds(static_cast<std::size_t>(n));
  StanceTurns turns(m, labels.first(static_cast<std::size_t>(n)), step_frames);
  std::vector<Transform> g(static_cast<std::size_t>(plan.joint_count()));
  const LegJoints legs = leg_joints(m);
  for (int f = 0; f < n; ++f) {
    leg_kinematics(plan.skeleton, legs, plan.frame(f), g);
    holds[static_cast<std::size_t>(f)] = turns.at(f, g, labels[static_cast<std::size_t>(f)]);
  }
  return holds;
}

// Stairs: each stance foot is planted flat on a tread (fit_on_tread, over
// its whole stance); between two plants the swing carries it from one to
// the next - along the stairs over the whole swing, up over its first 60 %
// (the toes clear the riser ahead) or down over its last 60 % (they clear
// the edge behind). Adds to `holds` (FootHold::lift, offset).
void plant_on_treads(const CycleModel& m, const Motion& plan, std::span<const FrameLabel> labels, const Ground& ground,
                     std::vector<std::array<FootHold, 2>>& holds) {
  const int n = static_cast<int>(holds.size());
  std::vector<Transform> g(static_cast<std::size_t>(plan.joint_count()));
  struct Plant {
    int first, last;
    FootExtent extent;
    double height = 0, move = 0;
  };
  std::vector<Plant> plants[2];
  auto along = [&](const Vec3& p) { return (p - ground.origin).dot(ground.direction); };
  const LegJoints legs = leg_joints(m);
  for (int f = 0; f < n; ++f) {
    leg_kinematics(plan.skeleton, legs, plan.frame(f), g);
    for (int side = 0; side < 2; ++side) {
      const bool stance = labels[static_cast<std::size_t>(f)].left_stance == (side == 1);
      auto& list = plants[side];
      if (!stance && f != 0 && f != n - 1) continue;  // (a foot in the air at the start or end stands where it is)
      if (!(stance && !list.empty() && list.back().last == f - 1)) list.push_back({f, f, {}});
      Plant& p = list.back();
      p.last = f;
      const FootPivots& foot = m.foot(side == 1);
      const Transform& a = g[static_cast<std::size_t>(foot.ankle)];
      const FootHold& h = holds[static_cast<std::size_t>(f)][static_cast<std::size_t>(side)];
      const double heel = along(h.apply(a.apply(foot.heel_local))), ball = along(h.apply(a.apply(foot.ball_local)));
      // (The toes as the plan bends them, and laid flat ahead of the ball, as
      // a foot rolled on its ball keeps them on a tread.)
      const Vec3 tip = foot.toe >= 0 ? h.apply(end_site_position(plan.skeleton, g, foot.toe)) : h.apply(a.apply(foot.ball_local));
      const Vec3 ball_at = h.apply(a.apply(foot.ball_local));
      const double toe = std::max(along(tip), ball + (tip - ball_at).norm());
      p.extent.lo = std::min({p.extent.lo, heel, ball, toe});
      p.extent.hi = std::max({p.extent.hi, heel, ball, toe});
      p.extent.ball_lo = std::min(p.extent.ball_lo, ball);
      p.extent.ball_hi = std::max(p.extent.ball_hi, ball);
    }
  }
  for (auto& list : plants)
    for (Plant& p : list) p.move = fit_on_tread(ground, p.extent, p.height);
  for (int side = 0; side < 2; ++side) {
    auto at = [&](int f) -> FootHold& { return holds[static_cast<std::size_t>(f)][static_cast<std::size_t>(side)]; };
    const auto& list = plants[side];
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Plant& p = list[i];
      for (int f = p.first; f <= p.last; ++f) at(f).lift = p.height, at(f).tread = p.move * ground.direction;
      if (i + 1 == list.size()) break;
      const Plant& q = list[i + 1];
      for (int f = p.last + 1; f < q.first; ++f) {
        const double u = static_cast<double>(f - p.last) / (q.first - p.last);
        const double w = q.height >= p.height ? smoothstep(u / 0.6) : smoothstep((u - 0.4) / 0.6);
        at(f).lift = p.height + w * (q.height - p.height);
        at(f).tread = (p.move + smoothstep(u) * (q.move - p.move)) * ground.direction;
      }
    }
    for (int f = 0; f < n; ++f) at(f).offset += at(f).tread;
  }
}

}  // namespace

namespace {

// One frame of the smooth root: the pivoting pose (in `pose`) moved by
// `shift` (horizontal, plus a pelvis drop in y), each foot rolled if out of
// reach, both legs solved. Returns the pelvis drop that would bring every
// ankle within reach without the soft limit (0 if none is needed).
struct FrameSolver {
  const CycleModel& m;
  const Ground& ground;
  const WalkOptions& opt;
  std::vector<Transform> before, g;  // FK of the plan's pose, of the moved pose (the legs' joints)
  LegIk legs[2];
  LegJoints leg_joints_;
  std::vector<Transform> kept;  // the plan's FK of every frame, the legs' joints (kept by the first pass for the second)
  FrameSolver(const CycleModel& model, const Ground& gr, const WalkOptions& o, const Motion& motion)
      : m(model), ground(gr), opt(o), before(static_cast<std::size_t>(motion.joint_count())), g(before.size()),
        leg_joints_(leg_joints(model)) {
    forward_kinematics(motion.skeleton, motion.frame(0), before);
    legs[0] = leg_of(motion.skeleton, false, before);
    legs[1] = leg_of(motion.skeleton, true, before);
    if (!leg_joints_.all) kept.resize(static_cast<std::size_t>(motion.frame_count()) * leg_joints_.list().size());
  }
  // The plan's frame f to solve next: its FK (`before`, the legs' joints),
  // computed and kept (`again` false) or recalled.
  void plan(int f, ConstPoseRef pose, bool again) {
    if (leg_joints_.all) return leg_kinematics(m.skeleton, leg_joints_, pose, before);
    const std::span<const int> joints = leg_joints_.list();
    Transform* k = kept.data() + static_cast<std::size_t>(f) * joints.size();
    if (!again) leg_kinematics(m.skeleton, leg_joints_, pose, before);
    for (std::size_t i = 0; i < joints.size(); ++i)
      again ? void(before[static_cast<std::size_t>(joints[i])] = k[i]) : void(k[i] = before[static_cast<std::size_t>(joints[i])]);
  }
  // A frame of the plan (after plan(pose)): the first pass (r = nullptr)
  // measures the drop needed and leaves `pose` alone; the second moves and solves it.
  double solve(PoseRef pose, const Vec3& shift, double heading, const FrameLabel& label, const std::array<FootHold, 2>& hold,
               WalkResult* r);
};

double FrameSolver::solve(PoseRef pose, const Vec3& shift, double heading, const FrameLabel& label,
                          const std::array<FootHold, 2>& hold, WalkResult* r) {
  const Skeleton& s = m.skeleton;
  if (r) pose.translations[0] += shift;
  shift_legs(leg_joints_, before, shift, g);  // (FK of the moved pose)
  bool limited = false;
  double drop = 0;
  const LegFrame frame{s, ground, before, shift, yaw_rotation(heading) * Vec3::UnitZ(), opt.soft_reach};
  for (int side = 0; side < 2; ++side) {
    const bool stance = label.left_stance == (side == 1);
    const LegPlacement placed = place_leg(frame, legs[side], m.foot(side == 1), hold[side],
                                          stance ? &label.pivot : nullptr, r != nullptr, pose, g);
    drop = std::max(drop, placed.drop);
    if (!r) continue;
    r->ground_lift_max = std::max(r->ground_lift_max, placed.lift);
    r->foot_roll_max = std::max(r->foot_roll_max, std::abs(placed.roll));
    r->leg_reach_max = std::max(r->leg_reach_max, placed.reach);
    limited = limited || placed.limited;
  }
  if (r) r->reach_limited_frames += limited;
  return drop;
}

// Largest value within `half_width` frames of each frame.
std::vector<double> running_max(const std::vector<double>& v, int half_width) {
  std::vector<double> out(v.size(), 0.0);
  const int n = static_cast<int>(v.size());
  for (int f = 0; f < n; ++f)
    for (int k = std::max(0, f - half_width); k <= std::min(n - 1, f + half_width); ++k)
      out[static_cast<std::size_t>(f)] = std::max(out[static_cast<std::size_t>(f)], v[static_cast<std::size_t>(k)]);
  return out;
}

}  // namespace

namespace {

// The pelvis's rise over uneven ground: the mean ground height under the two
// ankles of the plan, averaged over one step twice (as the root's travel).
std::vector<Vec3> ground_lift(const Ground& ground, const Motion& motion, double step_frames, bool rest_at_end,
                              std::span<const std::array<FootHold, 2>> holds) {
  const int n = motion.frame_count();
  std::vector<Vec3> lift(static_cast<std::size_t>(n), Vec3::Zero());
  if (ground.flat()) return lift;
  if (ground.stepped()) {  // (the heights the feet are planted and carried at, and their moves onto the treads)
    for (int f = 0; f < n; ++f) {
      const auto& h = holds[static_cast<std::size_t>(f)];
      lift[static_cast<std::size_t>(f)] = 0.5 * (h[0].tread + h[1].tread) + Vec3(0, 0.5 * (h[0].lift + h[1].lift), 0);
    }
    return window_average(window_average(lift, step_frames, rest_at_end), step_frames, rest_at_end);
  }
  const Skeleton& s = motion.skeleton;
  const int feet[2] = {s.roles[Role::LeftAnkle], s.roles[Role::RightAnkle]};
  std::vector<Transform> g(static_cast<std::size_t>(s.joint_count()));
  for (int f = 0; f < n; ++f) {
    forward_kinematics(s, motion.frame(f), g);
    double h = 0;
    for (int j : feet) h += 0.5 * ground.height(g[static_cast<std::size_t>(j)].translation);
    lift[static_cast<std::size_t>(f)] = Vec3(0, h, 0);
  }
  return window_average(window_average(lift, step_frames, rest_at_end), step_frames, rest_at_end);
}

}  // namespace

void smooth_root_motion(const CycleModel& m, const Ground& ground, std::span<const Vec3> floor_offset, double step_frames,
                        const WalkOptions& opt, WalkResult& r) {
  Motion& motion = r.motion;
  const int n = motion.frame_count();
  if (n < 2 || static_cast<int>(floor_offset.size()) != n) return;
  const std::vector<Vec3> smooth =
      window_average(window_average(floor_offset, step_frames, opt.stop), step_frames, opt.stop);
  std::vector<std::array<FootHold, 2>> holds(static_cast<std::size_t>(n));
  // (Off stairs the feet's turns are fed in the first pass, from its FK of the plan.)
  const bool turns_in_pass = opt.turn_on_ball && !ground.stepped() && static_cast<int>(r.labels.size()) >= n;
  if (opt.turn_on_ball && !turns_in_pass) holds = hold_stance_yaw(m, motion, r.labels, step_frames);
  if (ground.stepped()) plant_on_treads(m, motion, r.labels, ground, holds);
  const std::vector<Vec3> lift = ground_lift(ground, motion, step_frames, opt.stop, holds);
  std::vector<Vec3> shift(static_cast<std::size_t>(n));
  for (std::size_t f = 0; f < shift.size(); ++f) shift[f] = horizontal(smooth[f] - floor_offset[f]) + lift[f];
  FrameSolver solver(m, ground, opt, motion);
  // First pass: where the legs, rolled, still cannot reach, the pelvis must
  // drop; the drop is spread smoothly (running maximum over a quarter step,
  // averaged over as much: never less than needed).
  std::vector<double> drop(static_cast<std::size_t>(n));
  StanceTurns turns(m, std::span<const FrameLabel>(r.labels).first(turns_in_pass ? static_cast<std::size_t>(n) : 0), step_frames);
  for (int f = 0; f < n; ++f) {
    solver.plan(f, motion.frame(f), false);
    if (turns_in_pass) holds[static_cast<std::size_t>(f)] = turns.at(f, solver.before, r.labels[static_cast<std::size_t>(f)]);
    drop[static_cast<std::size_t>(f)] = solver.solve(motion.frame(f), shift[static_cast<std::size_t>(f)], r.heading[static_cast<std::size_t>(f)],
                                                     r.labels[static_cast<std::size_t>(f)], holds[static_cast<std::size_t>(f)], nullptr);
  }
  // (On stairs the drop needed changes by a tread's rise from step to step:
  // spread over half a step, averaged over a step.)
  const int quarter = std::max(1, static_cast<int>(std::ceil(step_frames / (ground.stepped() ? 2 : 4))));
  const std::vector<double> envelope = running_max(drop, quarter);
  std::vector<Vec3> lowered(static_cast<std::size_t>(n));
  for (std::size_t f = 0; f < lowered.size(); ++f) lowered[f] = Vec3(0, -envelope[f], 0);
  lowered = window_average(lowered, 2.0 * quarter, true);
  for (int f = 0; f < n; ++f) {
    const Vec3 d = shift[static_cast<std::size_t>(f)] + lowered[static_cast<std::size_t>(f)];
    r.pelvis_drop_max = std::max(r.pelvis_drop_max, -lowered[static_cast<std::size_t>(f)].y());
    solver.plan(f, motion.frame(f), true);
    solver.solve(motion.frame(f), d, r.heading[static_cast<std::size_t>(f)], r.labels[static_cast<std::size_t>(f)],
                 holds[static_cast<std::size_t>(f)], &r);
  }
}

}  // namespace legwork::walkcycle
