#include <legwork/walkcycle/offline/walk.hpp>
#include <legwork/core/rotation.hpp>

#include <legwork/core/interpolate.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::walkcycle {

namespace {

// Model-space heel and ball of both feet for one pose: [left?1:0... see index].
struct FootPoints {
  Vec3 p[2][2];  // [0 = right, 1 = left][0 = heel, 1 = ball]
  const Vec3& get(bool left, Pivot pv) const { return p[left ? 1 : 0][pv == Pivot::Heel ? 0 : 1]; }
};

FootPoints foot_points(const CycleModel& m, ConstPoseRef pose) {
  FootPoints f;
  for (int side = 0; side < 2; ++side)
    for (int k = 0; k < 2; ++k) f.p[side][k] = foot_point(m, pose, side == 1, k == 0 ? Pivot::Heel : Pivot::Ball);
  return f;
}

// Floor offset C that keeps `pivot_prev` (world, previous frame) under the
// same foot point now: world = yaw_rotation(theta) * model + C.
Vec3 planted_offset(const Vec3& world_prev, const Vec3& model_now, double theta) {
  return horizontal(world_prev - yaw_rotation(theta) * model_now);
}


}  // namespace

double step_length(const CycleModel& m) {
  Pose pose(m.skeleton);
  sample_cycle(m, 0.0, pose.ref());
  FootPoints prev = foot_points(m, pose);
  Vec3 c = Vec3::Zero();
  // Fine steps so the figure does not depend on the output rate.
  const int sub = 8;
  for (int i = 1; i <= m.frames_per_cycle * sub; ++i) {
    const double t = static_cast<double>(i) / sub;
    sample_cycle(m, t, pose.ref());
    const FootPoints cur = foot_points(m, pose);
    const StanceAt s = stance_at(m, t - 0.5 / sub);
    c = planted_offset(prev.get(s.left, s.pivot) + c, cur.get(s.left, s.pivot), 0.0);
    prev = cur;
  }
  return c.norm() / 2.0;
}

// How far the body travels during a stop step (the cycle blending into the
// standing pose over one step, from a contact), straight ahead.
double stop_advance(const CycleModel& m) {
  const double half = m.half_cycle();
  Pose cyc(m.skeleton), pose(m.skeleton);
  sample_cycle(m, 0.0, pose.ref());
  FootPoints prev = foot_points(m, pose);
  Vec3 c = Vec3::Zero();
  const int sub = 8;
  for (int i = 1; i <= static_cast<int>(half) * sub; ++i) {
    const double t = static_cast<double>(i) / sub;
    sample_cycle(m, t, cyc.ref());
    blend_poses(cyc, m.stand, smoothstep(t / half), pose.ref());
    const FootPoints cur = foot_points(m, pose);
    const StanceAt s = stance_at(m, t - 0.5 / sub);
    c = planted_offset(prev.get(true, s.pivot) + c, cur.get(true, s.pivot), 0.0);
    prev = cur;
  }
  return c.norm();
}

namespace {

// One walk along a path: walk_path's state and its stages.
class PathWalk {
 public:
  PathWalk(const CycleModel& m, const Path& path, const WalkOptions& opt);
  WalkResult run();

 private:
  double heading_at(double t) const;
  void decide_headings(int f, double t);
  double decide_heading(int k, const Vec3& here, const Vec3& prev_here, double remaining) const;
  bool local_pose(double t);
  FrameLabel label_at(double t, bool stopping) const;
  void place(int f, double theta, const FootPoints& cur, const FrameLabel& label);
  void record(int f, double theta, const FootPoints& cur, const FrameLabel& label);
  void finish();

  const CycleModel& m;
  const Path& path;
  const WalkOptions& opt;
  WalkResult r;
  double out_fps = 0, dt = 0, half = 0, L = 0, lookahead = 0, hold = 0, stop_travel = 0;
  std::vector<double> target;
  int stop_step = -1;
  double end_time = -1;
  double s_track = 0;
  int seg_track = 0;
  Vec3 last_here = Vec3::Zero();
  int written = 0;
  Pose local, stand_blend, world;
  FootPoints prev{};
  Vec3 c = Vec3::Zero();
  double theta_prev = 0;
  int last_step_recorded = -1;
};

PathWalk::PathWalk(const CycleModel& model, const Path& p, const WalkOptions& o)
    : m(model), path(p), opt(o), local(model.skeleton), stand_blend(model.skeleton), world(model.skeleton) {
  out_fps = opt.fps > 0 ? opt.fps : m.fps;
  dt = m.fps / out_fps;  // cycle frames per output frame
  half = m.half_cycle();
  r.step_length = step_length(m);
  r.path_length = path.length();
  L = r.step_length;
  if (opt.steps < 0 && L < 0.01)
    throw Error("the walk advances only " + std::to_string(L * 1000) +
                " mm per step; its key poses do not move the stance foot backwards, so it cannot follow a path");
  lookahead = std::max(opt.lookahead_steps * L, 0.05);  // lead of the heading decisions
  hold = half / 2;
  stop_travel = opt.steps < 0 && opt.stop ? stop_advance(m) : 0.5 * L;
  target = {std::atan2(path.tangent(0).x(), path.tangent(0).z())};
  stop_step = opt.steps >= 0 ? opt.steps : -1;
  end_time = opt.steps >= 0 && !opt.stop ? opt.steps * half : -1;
  last_here = path.points.front();
}

double PathWalk::heading_at(double t) const {
  const int j = static_cast<int>(std::floor(t / half + 0.5));
  const double a = target[static_cast<std::size_t>(std::max(0, j - 1))];
  const double b = target[static_cast<std::size_t>(std::max(0, j))];
  return a + (b - a) * smoothstep((t - (j - 0.5) * half) / half);
}

// The path's direction where the body will be once this heading has blended
// in (a step on: the chord over the step around s + lead), steered back
// towards the path in proportion to how far off it is.
double PathWalk::decide_heading(int k, const Vec3& here, const Vec3& prev_here, double remaining) const {
  double th = target.back();
  if (stop_step >= 0 && k > stop_step) return th;  // stopping: keep the last heading
  if (!(remaining > 0.25 * L)) return th;
  const Vec3 chord = path.at(s_track + lookahead + 0.5 * L) - path.at(s_track + lookahead - 0.5 * L);
  const Vec3 t0 = path.tangent(s_track);
  // (Averaged with the previous decision's position: the body sways
  // to the stance side every step, which is not an error to steer out.)
  const Vec3 steady = k >= 2 ? Vec3(0.5 * (here + prev_here)) : here;
  const double off_left = (steady - path.at(s_track)).dot(Vec3(t0.z(), 0, -t0.x()));
  th = std::atan2(chord.x(), chord.z()) - std::atan(off_left / (2 * L));
  while (th - target.back() > kPi) th -= 2 * kPi;
  while (th - target.back() < -kPi) th += 2 * kPi;
  return th;
}

// Heading decisions for every step whose blend has begun, from where the
// character is now.
void PathWalk::decide_headings(int f, double t) {
  const int need = static_cast<int>(std::floor(t / half + 0.5));
  while (static_cast<int>(target.size()) <= need) {
    const int k = static_cast<int>(target.size());
    const Vec3 here = f > 0 ? horizontal(r.motion.frame(f - 1).translations[0]) : path.points.front();
    double dist = 0;
    s_track = std::max(s_track, path.project(here, seg_track, s_track + 3 * L + lookahead, &seg_track, &dist));
    const double remaining = path.length() - s_track;
    const Vec3 prev_here = last_here;
    last_here = here;
    const double th = decide_heading(k, here, prev_here, remaining);
    // Stop when going on would overshoot the end by more than stopping now
    // falls short: from mid-step, half a step remains before the stop
    // step, which itself travels `stop_travel`.
    if (opt.steps < 0 && stop_step < 0 && remaining - 0.5 * L - stop_travel < 0.5 * L) {
      if (opt.stop) stop_step = k;
      else end_time = k * half;
    }
    target.push_back(th);
  }
}

// Local (in-place) pose: the cycle, blended into the standing pose while
// stopping (returns whether it is).
bool PathWalk::local_pose(double t) {
  sample_cycle(m, t, local.ref());
  if (!(stop_step >= 0 && opt.stop && t >= stop_step * half)) return false;
  const double w = smoothstep((t - stop_step * half) / half);
  blend_poses(local, m.stand, w, stand_blend.ref());
  std::swap(local, stand_blend);
  return true;
}

FrameLabel PathWalk::label_at(double t, bool stopping) const {
  StanceAt s = stance_at(m, std::max(0.0, t - 0.5 * dt));
  if (stop_step >= 0 && s.step > stop_step) {
    s.step = stop_step;
    s.left = stop_step % 2 == 0;
    s.pivot = Pivot::Ball;
  }
  return {s.step, s.left, s.pivot, stopping};
}

// World pose: the whole in-place body turned by the heading about y and
// placed so the pivot stays put.
void PathWalk::place(int f, double theta, const FootPoints& cur, const FrameLabel& label) {
  if (f == 0) {
    c = horizontal(path.points.front() - yaw_rotation(theta) * horizontal(local.translations[0]));
  } else {
    const Vec3 was = yaw_rotation(theta_prev) * prev.get(label.left_stance, label.pivot) + c;
    c = planted_offset(was, cur.get(label.left_stance, label.pivot), theta);
  }
  world.rotations = local.rotations;
  world.translations = local.translations;
  world.rotations[0] = yaw_rotation(theta) * local.rotations[0];
  world.translations[0] = yaw_rotation(theta) * local.translations[0] + c;
  Motion& out = r.motion;
  if (f >= out.frame_count()) out.resize(2 * out.frame_count());
  out.set_frame(f, world);
  written = f + 1;
}

// Per-frame results: heading, label, footsteps, deviation from the path.
void PathWalk::record(int f, double theta, const FootPoints& cur, const FrameLabel& label) {
  r.heading.push_back(theta);
  r.labels.push_back(label);
  if (label.step != last_step_recorded && (stop_step < 0 || label.step <= stop_step)) {
    last_step_recorded = label.step;
    Footstep fs;
    fs.heel = horizontal(yaw_rotation(theta) * cur.get(label.left_stance, Pivot::Heel) + c);
    fs.ball = horizontal(yaw_rotation(theta) * cur.get(label.left_stance, Pivot::Ball) + c);
    fs.heading = theta;
    fs.left = label.left_stance;
    fs.step = label.step;
    fs.frame = f;
    r.footsteps.push_back(fs);
  }
  if (!label.stopping) {  // (past the end, distance to the end point is not deviation)
    double dist = 0;
    int seg = seg_track;
    path.project(world.translations[0], std::max(0, seg_track - 2), s_track + 3 * L + lookahead, &seg, &dist);
    r.max_path_deviation = std::max(r.max_path_deviation, dist);
  }
}

void PathWalk::finish() {
  Motion& out = r.motion;
  out.resize(written);
  if (r.labels.size() > 1) r.labels[0] = r.labels[1];
  // The other foot, where it ends up beside the stance foot.
  if (opt.stop && out.frame_count() > 0) {
    const int lf = out.frame_count() - 1;
    const bool other_left = !r.labels.back().left_stance;
    const Vec3 h = horizontal(yaw_rotation(theta_prev) * prev.get(other_left, Pivot::Heel) + c);
    const Vec3 b = horizontal(yaw_rotation(theta_prev) * prev.get(other_left, Pivot::Ball) + c);
    r.footsteps.push_back({h, b, theta_prev, other_left, r.labels.back().step + 1, lf});
  }
  r.steps = r.labels.empty() ? 0 : r.labels.back().step + 1;
  r.turning = target.back() - target.front();
  for (std::size_t i = 1; i < target.size(); ++i) r.turning_abs += std::abs(target[i] - target[i - 1]);
  r.end_distance = out.frame_count() ? (horizontal(out.frame(out.frame_count() - 1).translations[0]) - path.points.back()).norm() : 0;
}

WalkResult PathWalk::run() {
  // Frames are written into a motion sized from the expected walk (grown by
  // doubling if needed, trimmed at the end) instead of appended one by one.
  const double expected_steps = opt.steps >= 0 ? opt.steps + 2.0 : path.length() / std::max(L, 0.01) + 3.0;
  r.motion = Motion(m.skeleton, out_fps, static_cast<int>(std::min(1e6, (expected_steps * half + half) / dt)) + 2);
  r.labels.reserve(static_cast<std::size_t>(r.motion.frame_count()));
  r.heading.reserve(static_cast<std::size_t>(r.motion.frame_count()));
  for (int f = 0;; ++f) {
    const double t = f * dt;
    if (stop_step >= 0 && end_time < 0) end_time = (stop_step + 1) * half + (opt.stop ? hold : 0.0);
    if (end_time >= 0 && t > end_time + 1e-9) break;
    if (f > 0 && t / half > opt.max_steps + 2)
      throw Error("walk: more than " + std::to_string(opt.max_steps) + " steps; is the path reachable?");
    decide_headings(f, t);
    const bool stopping = local_pose(t);
    const FootPoints cur = foot_points(m, local);
    const double theta = heading_at(t);
    const FrameLabel label = label_at(t, stopping);
    place(f, theta, cur, label);
    record(f, theta, cur, label);
    prev = cur;
    theta_prev = theta;
  }
  finish();
  return std::move(r);
}

}  // namespace

WalkResult walk_path(const CycleModel& m, const Path& path, const WalkOptions& opt) { return PathWalk(m, path, opt).run(); }

}  // namespace legwork::walkcycle
