#include <legwork/walkcycle/offline/measure.hpp>
#include <legwork/core/stats.hpp>

#include <legwork/core/fk.hpp>

#include <algorithm>
#include <limits>
#include <cmath>
#include <map>

namespace legwork::walkcycle {

namespace {

Vec3 pivot_world(const CycleModel& m, std::span<const Transform> g, bool left, Pivot pv) {
  const FootPivots& f = m.foot(left);
  return g[static_cast<std::size_t>(f.ankle)].apply(pv == Pivot::Heel ? f.heel_local : f.ball_local);
}

}  // namespace

SlipReport measure_stance_slip(const CycleModel& m, const Motion& walk, std::span<const FrameLabel> labels,
                               const Ground& ground) {
  SlipReport r;
  const int n = walk.frame_count();
  if (n < 2 || static_cast<int>(labels.size()) != n) return r;
  std::vector<Transform> g(static_cast<std::size_t>(walk.joint_count()));
  std::vector<Transform> g_prev(g.size());
  forward_kinematics(walk.skeleton, walk.frame(0), g_prev);
  std::map<int, double> per_step;
  Vec3 anchor = Vec3::Zero();
  bool down = false;
  double phase_max = 0, sum = 0;
  for (int f = 1; f < n; ++f) {
    forward_kinematics(walk.skeleton, walk.frame(f), g);
    const FrameLabel& l = labels[static_cast<std::size_t>(f)];
    const FrameLabel& lp = labels[static_cast<std::size_t>(f - 1)];
    const bool new_phase = f == 1 || l.step != lp.step || l.left_stance != lp.left_stance || l.pivot != lp.pivot;
    if (new_phase) {
      if (f > 1) sum += phase_max, ++r.phases;
      phase_max = 0;
      // Where the pivot was as the phase began, if it was on the ground.
      const Vec3 was = pivot_world(m, g_prev, l.left_stance, l.pivot);
      down = was.y() - ground.height(was) <= kFootDownTolerance;
      anchor = was;
    }
    std::swap(g, g_prev);
    const Vec3 p = pivot_world(m, g_prev, l.left_stance, l.pivot);
    if (p.y() - ground.height(p) > kFootDownTolerance) {  // in the air: not slipping; anchored again when down
      down = false;
      continue;
    }
    if (!down) down = true, anchor = p;
    const double mm = std::hypot(p.x() - anchor.x(), p.z() - anchor.z()) * 1000.0;
    phase_max = std::max(phase_max, mm);
    per_step[l.step] = std::max(per_step[l.step], mm);
    if (mm > r.max_mm) r.max_mm = mm, r.worst_step = l.step;
  }
  sum += phase_max, ++r.phases;
  r.mean_mm = sum / r.phases;
  for (auto& [s, v] : per_step) r.per_step_mm.push_back(v);
  return r;
}

GroundContactReport measure_ground_contact(const CycleModel& m, const Motion& walk, std::span<const FrameLabel> labels,
                                           const Ground& ground) {
  GroundContactReport r;
  const int n = std::min(walk.frame_count(), static_cast<int>(labels.size()));
  std::vector<Transform> g(static_cast<std::size_t>(walk.joint_count()));
  auto above = [&](const Vec3& p) { return (p.y() - ground.height(p)) * 1000.0; };
  for (int f = 0; f < n; ++f) {
    forward_kinematics(walk.skeleton, walk.frame(f), g);
    for (bool left : {true, false}) {
      const FootPivots& foot = m.foot(left);
      double low = std::min(above(pivot_world(m, g, left, Pivot::Heel)), above(pivot_world(m, g, left, Pivot::Ball)));
      if (foot.toe >= 0) low = std::min(low, above(end_site_position(m.skeleton, g, foot.toe)));
      if (-low > r.penetration_mm) r.penetration_mm = -low, r.penetration_frame = f;
      if (left == labels[static_cast<std::size_t>(f)].left_stance && low > r.stance_float_mm) r.stance_float_mm = low, r.float_frame = f;
    }
  }
  return r;
}

namespace {

// One foot point's contact over a stance: where it came down, if it is down.
struct PointContact {
  bool down = false;
  Vec3 anchor = Vec3::Zero();
  // Horizontal distance from where it came down (0 when it just did), mm;
  // negative while the point is up.
  double track(const Vec3& p, double height_above) {
    if (height_above > kFootDownTolerance) return down = false, -1.0;
    if (!down) down = true, anchor = p;
    return std::hypot(p.x() - anchor.x(), p.z() - anchor.z()) * 1000.0;
  }
};

double yaw_of(const Vec3& heel, const Vec3& ball) { return std::atan2(ball.x() - heel.x(), ball.z() - heel.z()); }

}  // namespace

FootTurnReport measure_foot_turning(const CycleModel& m, const Motion& walk, std::span<const FrameLabel> labels,
                                    const Ground& ground) {
  FootTurnReport r;
  const int n = std::min(walk.frame_count(), static_cast<int>(labels.size()));
  std::vector<Transform> g(static_cast<std::size_t>(walk.joint_count()));
  PointContact heel, ball;
  bool flat = false, on_ball = false;
  double flat_yaw = 0, ball_yaw = 0;
  for (int f = 0; f < n; ++f) {
    const FrameLabel& l = labels[static_cast<std::size_t>(f)];
    if (f == 0 || l.step != labels[static_cast<std::size_t>(f - 1)].step) heel = {}, ball = {}, flat = on_ball = false;
    forward_kinematics(walk.skeleton, walk.frame(f), g);
    const Vec3 h = pivot_world(m, g, l.left_stance, Pivot::Heel), b = pivot_world(m, g, l.left_stance, Pivot::Ball);
    const double hs = heel.track(h, h.y() - ground.height(h)), bs = ball.track(b, b.y() - ground.height(b));
    r.heel_slip_mm = std::max(r.heel_slip_mm, hs);
    r.ball_slip_mm = std::max(r.ball_slip_mm, bs);
    const double yaw = yaw_of(h, b);
    auto change = [&](double from) { return std::abs(rad2deg(std::remainder(yaw - from, 2 * kPi))); };
    if (hs >= 0 && bs >= 0) {
      if (!flat) flat = true, flat_yaw = yaw;
      if (change(flat_yaw) > r.twist_deg) r.twist_deg = change(flat_yaw), r.worst_step = l.step;
    } else {
      flat = false;
    }
    if (hs < 0 && bs >= 0) {
      if (!on_ball) on_ball = true, ball_yaw = yaw;
      r.turn_on_ball_deg = std::max(r.turn_on_ball_deg, change(ball_yaw));
    } else {
      on_ball = false;
    }
  }
  return r;
}

TreadReport measure_treads(const CycleModel& m, const Motion& walk, std::span<const FrameLabel> labels, const Ground& ground) {
  TreadReport r;
  if (!ground.stepped()) return r;
  const int n = std::min(walk.frame_count(), static_cast<int>(labels.size()));
  std::vector<Transform> g(static_cast<std::size_t>(walk.joint_count()));
  auto tread = [&](double along) { return along < 0 ? 0 : std::min(ground.count, static_cast<int>(std::floor(along / ground.run)) + 1); };
  r.ball_margin_mm = std::numeric_limits<double>::infinity();
  int last_step = -1, last_tread = -1;
  for (int f = 0; f < n; ++f) {
    const FrameLabel& l = labels[static_cast<std::size_t>(f)];
    forward_kinematics(walk.skeleton, walk.frame(f), g);
    const Vec3 b = pivot_world(m, g, l.left_stance, Pivot::Ball);
    if (b.y() - ground.height(b) > kFootDownTolerance) continue;
    const double along = (b - ground.origin).dot(ground.direction);
    const double k = std::clamp(std::round(along / ground.run), 0.0, ground.count - 1.0);  // the nearest riser
    r.ball_margin_mm = std::min(r.ball_margin_mm, 1e3 * std::abs(along - k * ground.run));
    if (l.step == last_step) continue;
    if (last_tread >= 0) r.treads_per_step_max = std::max(r.treads_per_step_max, std::abs(tread(along) - last_tread));
    last_step = l.step, last_tread = tread(along);
    ++r.stances;
  }
  if (r.stances == 0) r.ball_margin_mm = 0;
  return r;
}

SeamReport measure_loop_seam(const CycleModel& m) {
  const double n = m.frames_per_cycle, h = 1e-3;
  Pose pose(m.skeleton);
  auto pos = [&](double t) {
    sample_cycle(m, t, pose.ref());
    return joint_positions(m.skeleton, pose);
  };
  // Left of the seam: t = N - h, N - 2h, N - 3h (sampled inside the last
  // segment, not wrapped); right of it: t = 0, h, 2h.
  const auto l1 = pos(n - h), l2 = pos(n - 2 * h), l3 = pos(n - 3 * h);
  const auto r0 = pos(0), r1 = pos(h), r2 = pos(2 * h);
  SeamReport s;
  for (std::size_t j = 0; j < r0.size(); ++j) {
    const Vec3 p_left = 3 * l1[j] - 3 * l2[j] + l3[j];
    const Vec3 v_left = (2.5 * l1[j] - 4 * l2[j] + 1.5 * l3[j]) / h * m.fps;
    const Vec3 v_right = (-1.5 * r0[j] + 2 * r1[j] - 0.5 * r2[j]) / h * m.fps;
    s.position_m = std::max(s.position_m, (p_left - r0[j]).norm());
    s.velocity_mps = std::max(s.velocity_mps, (v_left - v_right).norm());
  }
  return s;
}

Arc trace_arc(const CycleModel& m, int joint, int samples_per_frame) {
  if (joint < 0 || joint >= m.skeleton.joint_count()) throw Error("arc: joint index out of range");
  Arc a;
  a.joint = joint;
  a.samples_per_frame = std::max(1, samples_per_frame);
  const int count = m.frames_per_cycle * a.samples_per_frame;
  Pose pose(m.skeleton);
  std::vector<Vec3> p(static_cast<std::size_t>(m.skeleton.joint_count()));
  for (int i = 0; i < count; ++i) {
    sample_cycle(m, static_cast<double>(i) / a.samples_per_frame, pose.ref());
    forward_positions(m.skeleton, pose, p);
    a.points.push_back(p[static_cast<std::size_t>(joint)]);
  }
  for (int step = 0; step < 2; ++step)
    for (double kf : m.key_frames) {
      const double t = kf + step * m.half_cycle();
      a.key_indices.push_back(static_cast<int>(std::lround(t * a.samples_per_frame)) % count);
    }
  return a;
}

ArcSmoothness arc_smoothness(const Arc& arc) {
  ArcSmoothness s;
  const int n = static_cast<int>(arc.points.size());
  if (n < 5) return s;
  auto P = [&](int i) -> const Vec3& { return arc.points[static_cast<std::size_t>(((i % n) + n) % n)]; };
  Vec3 lo = arc.points.front(), hi = arc.points.front();
  for (const auto& p : arc.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  s.extent_m = (hi - lo).norm();
  double mean_seg = 0;
  for (int i = 0; i < n; ++i) mean_seg += (P(i + 1) - P(i)).norm();
  mean_seg /= n;
  // Turning angle per point, NaN where the joint nearly stops.
  std::vector<double> turn(static_cast<std::size_t>(n), std::nan(""));
  for (int i = 0; i < n; ++i) {
    const Vec3 a = P(i) - P(i - 1), b = P(i + 1) - P(i);
    if (a.norm() < 0.05 * mean_seg || b.norm() < 0.05 * mean_seg) continue;
    turn[static_cast<std::size_t>(i)] = rad2deg(std::atan2(a.cross(b).norm(), a.dot(b)));
  }
  for (int i = 0; i < n; ++i) {
    const double a = turn[static_cast<std::size_t>(i)], b = turn[static_cast<std::size_t>((i + 1) % n)];
    if (std::isnan(a) || std::isnan(b)) continue;
    if (std::abs(b - a) > s.max_curvature_jump_deg) {
      s.max_curvature_jump_deg = std::abs(b - a);
      s.jump_frame = static_cast<double>((i + 1) % n) / arc.samples_per_frame;
    }
  }
  std::vector<double> jerk(static_cast<std::size_t>(n));
  double best = 0;
  for (int i = 0; i < n; ++i) {
    const double j = (P(i + 2) - 3 * P(i + 1) + 3 * P(i) - P(i - 1)).norm();
    jerk[static_cast<std::size_t>(i)] = j;
    if (j > best) best = j, s.jerk_frame = (i + 0.5) / arc.samples_per_frame;
  }
  const double mid = median(std::move(jerk));
  s.jerk_ratio = mid > 1e-15 ? best / mid : 0.0;
  return s;
}

FloorReport cycle_floor_contact(const CycleModel& m) {
  FloorReport r;
  r.lowest_m = 1e9;
  CycleModel unclamped = m;
  unclamped.floor_clamp = false;
  Pose p(m.skeleton);
  for (int i = 0; i < 4 * m.frames_per_cycle; ++i) {
    const double t = i / 4.0;
    sample_cycle(m, t, p.ref());
    const double lo = lowest_foot_height(m, p);
    if (lo < r.lowest_m) r.lowest_m = lo, r.at_frame = t;
    sample_cycle(unclamped, t, p.ref());
    const double dip = -lowest_foot_height(m, p);
    if (dip > r.max_lift_m) r.max_lift_m = dip, r.lift_frame = t;
  }
  return r;
}

std::array<double, kKeyCount + 1> key_foot_heights(const CycleModel& m) {
  std::array<double, kKeyCount + 1> out{};
  std::vector<Transform> g(static_cast<std::size_t>(m.skeleton.joint_count()));
  for (int k = 0; k <= kKeyCount; ++k) {
    forward_kinematics(m.skeleton, m.step_keys[static_cast<std::size_t>(k)], g);
    double lo = 1e9;
    for (bool left : {true, false}) {
      lo = std::min(lo, pivot_world(m, g, left, Pivot::Heel).y());
      lo = std::min(lo, pivot_world(m, g, left, Pivot::Ball).y());
      const FootPivots& f = m.foot(left);
      if (f.toe >= 0) lo = std::min(lo, end_site_position(m.skeleton, g, f.toe).y());
    }
    out[static_cast<std::size_t>(k)] = lo;
  }
  return out;
}

RootMotionReport measure_root_motion(const Motion& walk, std::span<const FrameLabel> labels) {
  RootMotionReport r;
  const int n = std::min(walk.frame_count(), static_cast<int>(labels.size()));
  auto cruising = [&](int f) { return labels[static_cast<std::size_t>(f)].step >= 1 && !labels[static_cast<std::size_t>(f)].stopping; };
  auto root = [&](int f) { const Vec3& p = walk.frame(f).translations[0]; return Vec3(p.x(), 0.0, p.z()); };
  double sum = 0;
  Vec3 v_prev = Vec3::Zero();
  bool have_prev = false;
  r.speed_min_mps = std::numeric_limits<double>::infinity();
  for (int f = 1; f < n; ++f) {
    if (!cruising(f) || !cruising(f - 1)) {
      have_prev = false;
      continue;
    }
    const Vec3 v = (root(f) - root(f - 1)) * walk.fps;
    const double speed = v.norm();
    r.speed_min_mps = std::min(r.speed_min_mps, speed);
    r.speed_max_mps = std::max(r.speed_max_mps, speed);
    sum += speed;
    ++r.frames;
    if (have_prev) r.accel_max_mps2 = std::max(r.accel_max_mps2, (v - v_prev).norm() * walk.fps);
    v_prev = v;
    have_prev = true;
  }
  for (int f = 1; f < n; ++f) {
    auto y = [&](int i) { return walk.frame(i).translations[0].y(); };
    r.vertical_speed_max_mps = std::max(r.vertical_speed_max_mps, std::abs(y(f) - y(f - 1)) * walk.fps);
    if (f + 1 < n)
      r.vertical_accel_max_mps2 = std::max(r.vertical_accel_max_mps2, std::abs(y(f + 1) - 2 * y(f) + y(f - 1)) * walk.fps * walk.fps);
  }
  if (r.frames == 0) return RootMotionReport{0, 0, 0, 0, 0, r.vertical_speed_max_mps, r.vertical_accel_max_mps2};
  r.speed_mean_mps = sum / r.frames;
  return r;
}

}  // namespace legwork::walkcycle
