#include <legwork/walkcycle/offline/walk.hpp>

#include "root_motion.hpp"
#include <legwork/core/rotation.hpp>

#include <legwork/core/interpolate.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <unordered_map>

namespace legwork::walkcycle {

namespace {

// Model-space heel and ball of both feet for one pose: [left?1:0... see index].
struct FootPoints {
  Vec3 p[2][2];  // [0 = right, 1 = left][0 = heel, 1 = ball]
  const Vec3& get(bool left, Pivot pv) const { return p[left ? 1 : 0][pv == Pivot::Heel ? 0 : 1]; }
};

FootPoints foot_points(const CycleModel& m, ConstPoseRef pose) {
  FootPoints f;
  for (int side = 0; side < 2; ++side) {
    const std::array<Vec3, 2> hb = heel_and_ball(m, pose, side == 1);
    f.p[side][0] = hb[0], f.p[side][1] = hb[1];
  }
  return f;
}

// Floor offset C that keeps `pivot_prev` (world, previous frame) under the
// same foot point now: world = yaw_rotation(theta) * model + C.
Vec3 planted_offset(const Vec3& world_prev, const Vec3& model_now, double theta) {
  return horizontal(world_prev - yaw_rotation(theta) * model_now);
}


}  // namespace

double step_length(const CycleModel& m) {
  if (m.step_travel >= 0) return m.step_travel;  // (build_cycle's, the same figure)
  return straight_pivot_travel(m, 8).back().norm() / 2.0;  // (fine steps: the figure does not depend on the output rate)
}

namespace {

// Output frames of a walk of `steps` steps (or, steps < 0, of `path_length`
// metres at `stride` metres a step), with the stop and the final hold.
double expected_frames(double half, double dt, int steps, double path_length, double stride) {
  const double expected_steps = steps >= 0 ? steps + 2.0 : path_length / std::max(stride, 0.01) + 3.0;
  return (expected_steps * half + half) / dt;
}

// Weight of the standing pose in the final two steps of a walk that ends:
// step k0 = stop_step - 1 shortens the stride to `amp` of the cycle's
// (weight rising to 1 - amp), the stop step settles into the standing pose
// (weight rising to 1). amp = 1 is the plain stop (cycle, then one blend step).
double final_weight(double t, double half, int stop_step, double amp) {
  const double u1 = (t - (stop_step - 1) * half) / half, u2 = (t - stop_step * half) / half;
  if (u1 <= 0) return 0.0;
  if (u2 <= 0) return (1 - amp) * smoothstep(u1);
  return (1 - amp) + amp * smoothstep(u2);
}

// Root travel (x = sideways, z = forward) of the cycle between times t0 and
// t1, starting straight ahead (the pivot rule of the walk; fine steps so it
// does not depend on the output rate). With amp >= 0 the walk ends: step
// stop_step - 1 shortened to amp, step `stop_step` the stop step (0 or 1),
// then the standing pose; the stop step turns by `turn` (radians, blended in
// from the middle of the step before it to its middle, as walk_path turns),
// about the planted foot.
Vec3 straight_advance(const CycleModel& m, double t0, double t1, double amp = -1, int stop_step = 1, double turn = 0) {
  const double half = m.half_cycle();
  Pose cyc(m.skeleton), pose(m.skeleton);
  auto local = [&](double t) {
    sample_cycle(m, t, cyc.ref());
    blend_poses(cyc, m.stand, amp < 0 ? 0.0 : final_weight(t, half, stop_step, amp), pose.ref());
  };
  auto heading = [&](double t) { return turn * smoothstep((t - (stop_step - 0.5) * half) / half); };
  local(t0);
  FootPoints prev = foot_points(m, pose);
  const Vec3 root0 = yaw_rotation(heading(t0)) * horizontal(pose.translations[0]);
  Vec3 c = Vec3::Zero();
  double th_prev = heading(t0);
  const int sub = std::max(1, static_cast<int>(std::ceil((t1 - t0) * 8)));
  for (int i = 1; i <= sub; ++i) {
    const double t = t0 + (t1 - t0) * i / sub, th = heading(t);
    local(t);
    const FootPoints cur = foot_points(m, pose);
    StanceAt st = stance_at(m, t - 0.5 * (t1 - t0) / sub);
    if (amp >= 0 && st.step > stop_step) st = {stop_step, stop_step % 2 == 0, Pivot::Ball};
    c = planted_offset(yaw_rotation(th_prev) * prev.get(st.left, st.pivot) + c, cur.get(st.left, st.pivot), th);
    prev = cur;
    th_prev = th;
  }
  return yaw_rotation(th_prev) * horizontal(pose.translations[0]) + c - root0;
}

// Travel of the final steps against the shortened stride and the stop
// step's turn, tabulated per walk (stride amp = 0, 1/8 .. 1; turn -90 to 90
// degrees in steps of 22.5), each column simulated when first needed,
// interpolated linearly: for a stop step 0 (a walk of one stop step, not
// turned) and for later stop steps by parity (1: odd, right foot; 2: even,
// left foot; the cycle repeats every two steps).
struct FinalTravel {
  static constexpr int kSamples = 9, kTurns = 9;
  static constexpr double kTurnMax = kPi / 2;
  explicit FinalTravel(const CycleModel& model) : m(model) {}
  Vec3 at(int stop, double amp, double turn = 0) const {
    const int row = stop == 0 ? 0 : 2 - stop % 2;
    if (row == 0) turn = 0;
    const double x = (std::clamp(turn, -kTurnMax, kTurnMax) + kTurnMax) / (2 * kTurnMax) * (kTurns - 1);
    const int i = std::min(kTurns - 2, static_cast<int>(x));
    const double w = x - i;
    const Vec3 a = column(row, i, amp);
    return w > 0 ? Vec3((1 - w) * a + w * column(row, i + 1, amp)) : a;
  }

 private:
  Vec3 column(int row, int col, double amp) const {
    auto& t = travel[static_cast<std::size_t>(row)][static_cast<std::size_t>(col)];
    if (!filled[static_cast<std::size_t>(row)][static_cast<std::size_t>(col)]) {
      const double half = m.half_cycle(), turn = -kTurnMax + 2 * kTurnMax * col / (kTurns - 1);
      for (int i = 0; i < kSamples; ++i)
        t[static_cast<std::size_t>(i)] = straight_advance(m, std::max(0, row - 1) * half, (row + 1.5) * half,
                                                          static_cast<double>(i) / (kSamples - 1), row, turn);
      filled[static_cast<std::size_t>(row)][static_cast<std::size_t>(col)] = true;
    }
    const double x = std::clamp(amp, 0.0, 1.0) * (kSamples - 1);
    const int i = std::min(kSamples - 2, static_cast<int>(x));
    return t[static_cast<std::size_t>(i)] + (x - i) * (t[static_cast<std::size_t>(i + 1)] - t[static_cast<std::size_t>(i)]);
  }
  const CycleModel& m;
  mutable std::array<std::array<std::array<Vec3, kSamples>, kTurns>, 3> travel{};
  mutable std::array<std::array<bool, kTurns>, 3> filled{};
};

// Straight travel per step of the cycle blended towards the standing pose by
// `w` throughout (a steady walk of shorter strides; one cycle, halved).
double blended_step_travel(const CycleModel& m, double w) {
  Pose cyc(m.skeleton), pose(m.skeleton);
  auto local = [&](double t) {
    sample_cycle(m, t, cyc.ref());
    blend_poses(cyc, m.stand, w, pose.ref());
  };
  local(0.0);
  FootPoints prev = foot_points(m, pose);
  const Vec3 root0 = horizontal(pose.translations[0]);
  Vec3 c = Vec3::Zero();
  const int sub = m.frames_per_cycle * 8;
  for (int i = 1; i <= sub; ++i) {
    const double t = static_cast<double>(i) / 8;
    local(t);
    const FootPoints cur = foot_points(m, pose);
    const StanceAt st = stance_at(m, t - 0.5 / 8);
    c = planted_offset(prev.get(st.left, st.pivot) + c, cur.get(st.left, st.pivot), 0.0);
    prev = cur;
  }
  return (horizontal(pose.translations[0]) + c - root0).norm() / 2;
}

}  // namespace

StairStride stair_stride(const CycleModel& m, const Path& path) {
  StairStride st;
  const Ground& g = path.ground;
  if (!g.stepped()) return st;
  // The risers along the path: where the ground's height jumps (2 cm samples).
  const double ds = 0.02;
  double h_prev = g.height(path.at(0.0));
  for (double s = ds; s <= path.length() + 1e-9; s += ds) {
    const double h = g.height(path.at(s));
    if (h != h_prev) {
      if (st.first_riser < 0) st.first_riser = s;
      st.last_riser = s;
    }
    h_prev = h;
  }
  if (st.first_riser < 0) return st;
  // One tread per step, or several steps per tread on treads longer than the stride.
  const double full = step_length(m);
  st.stride = g.run / std::max(1.0, std::ceil(g.run / full - 1e-9));
  if (st.stride >= full) return st;
  double lo = 0, hi = 1;  // weight of the standing pose: the travel falls as it rises
  if (blended_step_travel(m, hi) > st.stride)
    throw Error("walk: stairs with " + std::to_string(g.run) + " m treads need strides of " + std::to_string(st.stride) +
                " m; even the standing pose travels more per step");
  for (int i = 0; i < 24; ++i) {
    const double mid = 0.5 * (lo + hi);
    (blended_step_travel(m, mid) > st.stride ? lo : hi) = mid;
  }
  st.weight = 0.5 * (lo + hi);
  return st;
}

namespace {

// One walk along a path: walk_path's state and its stages.
class PathWalk {
 public:
  PathWalk(const CycleModel& m, const Path& path, const WalkOptions& opt, const FinalTravel& final_steps,
           const Vec3& aim_offset = Vec3::Zero());
  // Walks the plan (the pivoting root); planned() has where it ended.
  void run();
  const WalkResult& planned() const { return r; }
  // The walk: the smooth root applied if asked, deviation and end measured.
  WalkResult take();

 private:
  double heading_at(double t) const;
  void decide_headings(int f, double t);
  double decide_heading(int k, const Vec3& here, const Vec3& prev_here, double remaining) const;
  bool local_pose(double t);
  FrameLabel label_at(double t, bool stopping) const;
  void place(int f, double theta, const FootPoints& cur, const FrameLabel& label);
  void record(int f, double theta, const FootPoints& cur, const FrameLabel& label);
  void finish();
  void measure_deviation();
  void measure_end();
  bool plan_final_steps(int k, const Vec3& start, double t_here);
  double solve_amplitude(double distance, int stop, double turn, Vec3* travel) const;
  double stairs_weight_at(double t) const;
  void decide_stairs(int k);

  const CycleModel& m;
  const Path& path;
  const WalkOptions& opt;
  const FinalTravel& finals;
  Vec3 aim;  // where the final steps aim: the path's end (plus a correction, see walk_path)
  WalkResult r;
  double out_fps = 0, dt = 0, half = 0, L = 0, lookahead = 0, hold = 0, stop_travel = 0;
  double final_travel = 0;  // straight root travel of the plain final two steps (cycle step + stop step)
  double amp = 1.0;         // stride of the step before the stop step (1 = the cycle's)
  std::vector<double> target;
  StairStride stairs;              // the stride fitted to the treads
  std::vector<double> stairs_w;    // per footstep j (landing at j * half): weight of the standing pose
  int stop_step = -1;
  double end_time = -1;
  double s_track = 0;
  int seg_track = 0;
  Vec3 last_here = Vec3::Zero();
  int written = 0;
  Pose local, stand_blend, world;
  FootPoints local_feet{};  // the foot points of `local` (local_pose)
  // The cycle's poses sampled so far and their foot points, by cycle time
  // within the cycle (sample_cycle's wrap): a walk's frames come back to the
  // same cycle times (every cycle when the output rate divides the cycle's),
  // each sampled once (the same values; at most kSampledMax kept).
  struct Sampled {
    Pose pose;
    FootPoints feet;
  };
  static constexpr std::size_t kSampledMax = 512;
  std::unordered_map<double, std::size_t> sampled_at;
  std::vector<Sampled> sampled;
  FootPoints prev{};
  Vec3 c = Vec3::Zero();
  double theta_prev = 0;
  int last_step_recorded = -1;
  std::vector<Vec3> offsets;  // c per frame (smooth root)
  struct Track {
    int segment = 0;
    double s = 0;
    bool stopping = false;
  };
  std::vector<Track> tracks;  // path tracking per frame (deviation)
};

PathWalk::PathWalk(const CycleModel& model, const Path& p, const WalkOptions& o, const FinalTravel& final_steps,
                   const Vec3& aim_offset)
    : m(model), path(p), opt(o), finals(final_steps), aim(horizontal(p.points.back() + aim_offset)), local(model.skeleton), stand_blend(model.skeleton), world(model.skeleton) {
  out_fps = opt.fps > 0 ? opt.fps : m.fps;
  dt = m.fps / out_fps;  // cycle frames per output frame
  half = m.half_cycle();
  r.step_length = step_length(m);
  r.path_length = path.length();
  r.root = opt.root;
  r.ground = path.ground;
  L = r.step_length;
  if (opt.steps == 0) throw Error("walk: steps must be at least 1 (a walk of 0 steps is the standing pose)");
  if (!path.ground.flat() && opt.root == RootMotion::Pivot)
    throw Error("walk: uneven ground (" + path.ground.describe() + ") needs the smooth root: the legs' IK puts the feet on it");
  if (!(opt.soft_reach > 0.5 && opt.soft_reach <= 1.0))
    throw Error("walk: soft_reach " + std::to_string(opt.soft_reach) + " is out of range (0.5, 1]: the fraction of a leg's length it may straighten to");
  if (opt.steps < 0 && L < 0.01)
    throw Error("the walk advances only " + std::to_string(L * 1000) +
                " mm per step; its key poses do not move the stance foot backwards, so it cannot follow a path");
  lookahead = std::max(opt.lookahead_steps * L, 0.05);  // lead of the heading decisions
  // The final hold: a quarter cycle; with the smooth root one step, so the
  // averaged root reaches the end of the walk while the body stands.
  hold = opt.root == RootMotion::Smooth ? half : half / 2;
  stop_travel = 0.5 * L;  // (without a stop, the walk just ends)
  target = {std::atan2(path.tangent(0).x(), path.tangent(0).z())};
  if (opt.fit_stairs_stride) stairs = stair_stride(m, path);
  stairs_w = {0.0, 0.0};
  r.stairs_stride = stairs.weight > 0 ? stairs.stride : 0.0;
  decide_stairs(0);
  stop_step = opt.steps > 0 ? opt.steps - 1 : -1;  // the stop step is the last of the `steps`
  end_time = opt.steps >= 0 && !opt.stop ? opt.steps * half : -1;
  last_here = path.points.front();
  if (opt.steps < 0 && opt.stop) {
    final_travel = finals.at(1, 1.0).z();
    plan_final_steps(0, path.points.front(), 0.0);  // a path shorter than two steps
  }
}

// Root travel of the final steps (from where step stop - 1 starts, or the
// walk's start) as a function of the shortened stride: forward travel grows
// with it; inverted by bisection (the stop step turned by `turn`). Returns the stride; `travel` receives the
// travel (x sideways as simulated, z forward).
double PathWalk::solve_amplitude(double distance, int stop, double turn, Vec3* travel) const {
  auto advance = [&](double a) { return finals.at(stop, a, turn); };
  double lo = 0, hi = 1;
  *travel = advance(1.0);
  if (distance >= travel->z()) return 1.0;
  *travel = advance(0.0);
  if (distance <= travel->z()) return 0.0;
  for (int i = 0; i < 30; ++i) {
    const double mid = 0.5 * (lo + hi);
    (advance(mid).z() < distance ? lo : hi) = mid;
  }
  *travel = advance(0.5 * (lo + hi));
  return 0.5 * (lo + hi);
}

// Ending at the path's end: once the end is within the final two steps'
// travel from where step k will start, step k becomes a shortened step (its
// stride solved so the walk stops on the end point) heading for the end, and
// step k + 1 the stop step, turned to the end tangent. A path shorter than
// that is walked in one stop step from a partly standing pose.
bool PathWalk::plan_final_steps(int k, const Vec3& here, double t_here) {
  if (stop_step >= 0) return false;
  const double theta = k == 0 ? target.front() : heading_at(t_here);
  const Vec3 start = here + yaw_rotation(theta) * (k == 0 ? Vec3::Zero() : straight_advance(m, t_here, k * half));
  const Vec3 to_end = horizontal(aim - start);
  const double distance = to_end.norm();
  if (distance > final_travel) return false;
  stop_step = k + 1;
  if (k == 0 && distance < finals.at(1, 0.0).z()) stop_step = 0;
  Vec3 travel = Vec3::Zero();
  const Vec3 t_end = path.tangent(path.length());
  double turn = 0;  // of the stop step, to the end tangent: it swings the root about the planted foot
  amp = solve_amplitude(distance, stop_step, turn, &travel);
  for (int i = 0; i < 4; ++i) {  // the sideways settle and the turn: solve on the forward part of the distance
    if (k > 0 && distance > 0.05 * L)
      turn = std::remainder(std::atan2(t_end.x(), t_end.z()) - (std::atan2(to_end.x(), to_end.z()) - std::atan2(travel.x(), travel.z())), 2 * kPi);
    const double forward = std::sqrt(std::max(0.0, distance * distance - travel.x() * travel.x()));
    amp = solve_amplitude(forward, stop_step, turn, &travel);
  }
  // (Simulated with the parity of the real stop step, so x is already the right side.)
  if (k > 0 && distance > 0.05 * L) target.back() = std::atan2(to_end.x(), to_end.z()) - std::atan2(travel.x(), travel.z());
  return true;
}

// Stairs: the footstep landing at (k + 1) * half takes the stairs' stride if
// the walk's own stride would put it on the flight or past a quarter tread
// before its first riser (so the approach shortens on the flat rather than
// skipping a tread), up to the first footstep on the top (half a tread past
// the last riser). Estimated at mid-step k - 1 from where the stance foot of
// step k - 1 stands, one stride on for step k (its own, decided before).
// Its stride blends in over the step before it lands (the swing).
void PathWalk::decide_stairs(int k) {
  if (static_cast<int>(stairs_w.size()) > k + 1) return;
  double w = 0;
  if (stairs.weight > 0) {
    double s0 = 0;
    if (!r.labels.empty()) {
      const Vec3 heel = horizontal(yaw_rotation(theta_prev) * prev.get(r.labels.back().left_stance, Pivot::Heel) + c);
      int seg = seg_track;
      double dist = 0;
      s0 = path.project(heel, std::max(0, seg_track - 2), s_track + 3 * L + lookahead, &seg, &dist);
    }
    const double next = s0 + (stairs_w.back() > 0 ? stairs.stride : L);  // step k's footstep
    if (next + L >= stairs.first_riser - 0.25 * path.ground.run && next + stairs.stride <= stairs.last_riser + 0.5 * path.ground.run)
      w = stairs.weight;
  }
  stairs_w.push_back(w);
}

double PathWalk::stairs_weight_at(double t) const {
  const int j = static_cast<int>(std::floor(t / half)) + 1;
  const auto at = [&](int i) { return stairs_w[static_cast<std::size_t>(std::clamp(i, 0, static_cast<int>(stairs_w.size()) - 1))]; };
  return at(j - 1) + (at(j) - at(j - 1)) * smoothstep(t / half - (j - 1));
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
  if (opt.steps < 0 && opt.stop && stop_step >= 0 && k == stop_step) {  // the stop step faces along the end tangent
    const Vec3 t_end = path.tangent(path.length());
    th = std::atan2(t_end.x(), t_end.z());
    while (th - target.back() > kPi) th -= 2 * kPi;
    while (th - target.back() < -kPi) th += 2 * kPi;
    return th;
  }
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
    if (opt.steps < 0 && stop_step < 0 && !opt.stop && remaining - 0.5 * L - stop_travel < 0.5 * L) end_time = k * half;
    target.push_back(th);
    decide_stairs(k);
    if (opt.steps < 0 && opt.stop) plan_final_steps(k, here, std::max(0, f - 1) * dt);
  }
}

// Local (in-place) pose: the cycle, blended into the standing pose while
// stopping (returns whether it is).
bool PathWalk::local_pose(double t) {
  const double period = m.frames_per_cycle;
  const auto known = sampled_at.find(t - period * std::floor(t / period));
  if (known != sampled_at.end()) {
    const Sampled& k = sampled[known->second];
    std::copy(k.pose.rotations.begin(), k.pose.rotations.end(), local.rotations.begin());
    std::copy(k.pose.translations.begin(), k.pose.translations.end(), local.translations.begin());
    local_feet = k.feet;
  } else {
    sample_cycle(m, t, local.ref());
    local_feet = foot_points(m, local);
    if (sampled.size() < kSampledMax) {
      sampled_at.emplace(t - period * std::floor(t / period), sampled.size());
      sampled.push_back({local, local_feet});
    }
  }
  const bool stopping = stop_step >= 0 && opt.stop;
  const double w = std::max(stopping ? final_weight(t, half, stop_step, amp) : 0.0, stairs_weight_at(t));
  if (w > 0) {
    blend_poses(local, m.stand, w, stand_blend.ref());
    std::swap(local, stand_blend);
    local_feet = foot_points(m, local);
  }
  return stopping && t >= stop_step * half;
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
  if (offsets.size() <= static_cast<std::size_t>(f)) offsets.resize(static_cast<std::size_t>(f) + 1);
  offsets[static_cast<std::size_t>(f)] = c;
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
  tracks.push_back({seg_track, s_track, label.stopping});
}

// Largest root distance from the path (forward-only tracking as walked).
void PathWalk::measure_deviation() {
  for (int f = 0; f < r.motion.frame_count(); ++f) {
    const Track& t = tracks[static_cast<std::size_t>(f)];
    if (t.stopping) continue;  // (past the end, distance to the end point is not deviation)
    double dist = 0;
    int seg = t.segment;
    path.project(r.motion.frame(f).translations[0], std::max(0, t.segment - 2), t.s + 3 * L + lookahead, &seg, &dist);
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
  measure_end();
}

// Where and how the walk ended against the path's end (with a step count,
// the path ends where the walk did: its length is the distance walked along it).
void PathWalk::measure_end() {
  const Motion& out = r.motion;
  if (out.frame_count() == 0) return;
  r.end_position = horizontal(out.frame(out.frame_count() - 1).translations[0]);
  r.travel = (r.end_position - horizontal(out.frame(0).translations[0])).norm();
  double s_end = path.length();
  if (opt.steps > 0) {
    int seg = 0;
    s_end = path.project(r.end_position, 0, path.length(), &seg, &r.end_distance);
    r.path_length = s_end;
  } else {
    r.end_distance = (r.end_position - path.points.back()).norm();
  }
  const Vec3 tan = path.tangent(s_end);
  double err = r.heading.back() - std::atan2(tan.x(), tan.z());
  while (err > kPi) err -= 2 * kPi;
  while (err < -kPi) err += 2 * kPi;
  r.end_heading_error = err;
}

WalkResult PathWalk::take() {
  if (opt.root == RootMotion::Smooth) {
    offsets.resize(static_cast<std::size_t>(r.motion.frame_count()));
    smooth_root_motion(m, path.ground, offsets, half / dt, opt, r);
  }
  measure_deviation();
  measure_end();
  return std::move(r);
}

void PathWalk::run() {
  // Frames are written into a motion sized from the expected walk (grown by
  // doubling if needed, trimmed at the end) instead of appended one by one.
  const double expected = expected_frames(half, dt, opt.steps, path.length(), L);
  if (!(expected <= opt.max_frames))
    throw Error("walk: about " + std::to_string(std::llround(std::min(expected, 1e18))) + " frames, more than the limit of " +
                std::to_string(opt.max_frames) + " frames a walk is made with");
  r.motion = Motion(m.skeleton, out_fps, static_cast<int>(expected) + 2);
  r.labels.reserve(static_cast<std::size_t>(r.motion.frame_count()));
  r.heading.reserve(static_cast<std::size_t>(r.motion.frame_count()));
  for (int f = 0;; ++f) {
    const double t = f * dt;
    if (stop_step >= 0 && end_time < 0) end_time = (stop_step + 1) * half + (opt.stop ? hold : 0.0);
    if (end_time >= 0 && t > end_time + 1e-9) break;
    if (f > 0 && t / half > opt.max_steps + 2)
      throw Error("walk: more than " + std::to_string(opt.max_steps) + " steps; is the path reachable?");
    if (f >= opt.max_frames)
      throw Error("walk: more than the limit of " + std::to_string(opt.max_frames) + " frames; is the path reachable?");
    decide_headings(f, t);
    const bool stopping = local_pose(t);
    const FootPoints cur = local_feet;
    const double theta = heading_at(t);
    const FrameLabel label = label_at(t, stopping);
    place(f, theta, cur, label);
    record(f, theta, cur, label);
    prev = cur;
    theta_prev = theta;
  }
  finish();
}

}  // namespace

double expected_walk_frames(const CycleModel& m, double path_length, const WalkOptions& opt) {
  const double dt = m.fps / (opt.fps > 0 ? opt.fps : m.fps);  // cycle frames per output frame
  return expected_frames(m.half_cycle(), dt, opt.steps, path_length, opt.steps >= 0 ? 0.0 : step_length(m));
}

// The final steps are planned from a prediction (straight travel, turned by
// the headings); on a path that still turns there the walk can stop a few
// centimetres off. Closed loop: walk again aiming past the end by the miss,
// up to three times, and keep the closest (deterministic: same input, same walk).
WalkResult walk_path(const CycleModel& model, const Path& path, const WalkOptions& opt) {
  // The smooth root's legs keep every foot above the ground themselves, so
  // its plan goes without the floor lift (which raises the whole body where
  // one foot would dip, leaving the planted foot floating); the lift only
  // moves the root up and down, so the plan's footprints are the same.
  CycleModel unlifted;
  const bool lift_by_legs = opt.root == RootMotion::Smooth && model.floor_clamp;
  if (lift_by_legs) {
    unlifted = model;
    unlifted.floor_clamp = false;
  }
  const CycleModel& m = lift_by_legs ? unlifted : model;
  const FinalTravel finals(m);
  auto best = std::make_unique<PathWalk>(m, path, opt, finals);
  best->run();
  if (opt.steps > 0 || !opt.stop) return best->take();
  // (The smooth root rests where the plan does, so the plans are compared
  // and only the best one is smoothed.)
  // The end moves with the aim smoothly only while the number of steps stays
  // the same, and on a path that hooks round in its last metre it moves less
  // than the aim (the final steps turn away from it): each correction is
  // scaled by how far the end moved for the last one (a secant step, up to
  // 4 times the miss), and one that does not get closer is halved, from the
  // best walk so far.
  Vec3 offset = Vec3::Zero(), miss = best->planned().end_position - horizontal(path.points.back());
  double gain = 1.0;
  for (int i = 0; i < opt.end_iterations && miss.norm() > 0.01; ++i) {
    const Vec3 trial = offset - gain * miss;
    auto again = std::make_unique<PathWalk>(m, path, opt, finals, trial);
    again->run();
    if (again->planned().end_distance < best->planned().end_distance) {
      // How far the end moved for the aim's move: the next correction is scaled by it (secant).
      const Vec3 now = again->planned().end_position - horizontal(path.points.back()), step = trial - offset;
      const double moved = (now - miss).dot(step) / step.squaredNorm();
      gain = 1.0 / std::clamp(moved, 0.25, 1.0);
      best = std::move(again);
      offset = trial;
      miss = now;
    } else {
      gain *= 0.5;
    }
  }
  return best->take();
}

}  // namespace legwork::walkcycle
