#include <legwork/walkcycle/cycle.hpp>
#include <legwork/core/rotation.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/mirror.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::walkcycle {

namespace {

Quat positive_w(Quat q) {
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return q;
}

double wrap(double t, double period) { return t - period * std::floor(t / period); }

// Where a time falls among a channel's keys: the segment [i, next] and the
// cubic Hermite weights of its two values and two slopes (the slopes' weights
// include the segment's length).
// (No default values: sample_cycle keeps an uninitialised array of them, each filled before use.)
struct Segment {
  int i, next;
  double c0, c1, c2, c3;
};

Segment locate(const double* times, int count, double n, double t) {
  Segment s;  // NOLINT(cppcoreguidelines-pro-type-member-init): every field is set below
  // Last key at or before t (keys are few; a linear scan is fastest).
  s.i = count - 1;
  if (t < times[0]) {
    t += n;
  } else {
    for (int k = 1; k < count; ++k)
      if (times[k] > t) {
        s.i = k - 1;
        break;
      }
  }
  s.next = s.i + 1 == count ? 0 : s.i + 1;
  const double t0 = times[s.i];
  const double t1 = times[s.next] + (s.next == 0 ? n : 0.0);
  const double h = t1 - t0;
  const double u = (t - t0) / h;
  const double u2 = u * u, u3 = u2 * u;
  s.c0 = 2 * u3 - 3 * u2 + 1;
  s.c1 = (u3 - 2 * u2 + u) * h;
  s.c2 = -2 * u3 + 3 * u2;
  s.c3 = (u3 - u2) * h;
  return s;
}

Vec3 blend(const CycleModel& m, const CycleModel::Channel& c, const Segment& s) {
  if (c.count == 1) return m.key_value[static_cast<std::size_t>(c.first)];
  const auto a = static_cast<std::size_t>(c.first + s.i), b = static_cast<std::size_t>(c.first + s.next);
  return s.c0 * m.key_value[a] + s.c1 * m.key_slope[a] + s.c2 * m.key_value[b] + s.c3 * m.key_slope[b];
}

// Cubic Hermite on one periodic channel; keys in [first, first+count).
Vec3 eval_channel(const CycleModel& m, const CycleModel::Channel& c, double t) {
  if (c.count == 1) return m.key_value[static_cast<std::size_t>(c.first)];
  return blend(m, c, locate(m.key_time.data() + c.first, c.count, m.frames_per_cycle, t));
}

struct Entry {
  double time;
  Quat rotation;
  Vec3 offset;
};

// Appends one channel's keys (sorted, wrapped into [0, N)) with slopes.
CycleModel::Channel add_channel(CycleModel& m, std::vector<Entry> entries, bool rotation) {
  const double n = m.frames_per_cycle;
  for (auto& e : entries) e.time = wrap(e.time, n);
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.time < b.time; });
  for (std::size_t i = 1; i < entries.size(); ++i)
    if (entries[i].time - entries[i - 1].time < 1e-6)
      throw Error("two keys of one joint fall on the same frame " + std::to_string(entries[i].time) +
                  " (check shift offsets against in-between frames)");
  CycleModel::Channel c;
  c.first = static_cast<int>(m.key_time.size());
  c.count = static_cast<int>(entries.size());
  if (rotation) {
    Eigen::Vector4d sum = Eigen::Vector4d::Zero();
    for (const auto& e : entries) sum += positive_w(e.rotation).coeffs();
    c.ref = sum.norm() > 1e-9 ? Quat(sum / sum.norm()) : Quat::Identity();
  }
  for (const auto& e : entries) {
    m.key_time.push_back(e.time);
    m.key_value.push_back(rotation ? rotation_log(c.ref.conjugate() * e.rotation) : e.offset);
  }
  const int k = c.count;
  for (int i = 0; i < k; ++i) {
    const int p = (i - 1 + k) % k, q = (i + 1) % k;
    const auto ti = static_cast<std::size_t>(c.first + i);
    const auto tp = static_cast<std::size_t>(c.first + p), tq = static_cast<std::size_t>(c.first + q);
    double hp = m.key_time[ti] - m.key_time[tp];
    double hn = m.key_time[tq] - m.key_time[ti];
    if (hp <= 0) hp += n;
    if (hn <= 0) hn += n;
    if (k == 1) {
      m.key_slope.push_back(Vec3::Zero());
      continue;
    }
    const Vec3 sp = (m.key_value[ti] - m.key_value[tp]) / hp;
    const Vec3 sn = (m.key_value[tq] - m.key_value[ti]) / hn;
    m.key_slope.push_back((hn * sp + hp * sn) / (hp + hn));
  }
  return c;
}

Pose full_pose(const Skeleton& skel, const KeyPose& k) {
  Pose p(skel);
  for (const auto& [j, q] : k.rotations) p.rotations[static_cast<std::size_t>(j)] = q;
  return p;
}

FootPivots make_foot(const Skeleton& skel, ConstPoseRef stand, Role ankle_role, Role toe_role) {
  FootPivots f;
  f.ankle = skel.roles[ankle_role];
  f.toe = skel.roles[toe_role];
  std::vector<int> chain;
  for (int j = f.ankle; j >= 0; j = skel.parents[static_cast<std::size_t>(j)]) chain.push_back(j);
  if (chain.size() > f.chain.size()) throw Error("leg chain longer than 16 joints; not supported");
  std::reverse(chain.begin(), chain.end());
  f.chain_length = static_cast<int>(chain.size());
  std::copy(chain.begin(), chain.end(), f.chain.begin());
  std::vector<Transform> g(static_cast<std::size_t>(skel.joint_count()));
  forward_kinematics(skel, stand, g);
  const Transform& a = g[static_cast<std::size_t>(f.ankle)];
  const Vec3 heel(a.translation.x(), 0.0, a.translation.z());
  f.heel_local = a.rotation.conjugate() * (heel - a.translation);
  Vec3 ball_world = heel;
  if (f.toe >= 0) {
    const Vec3 t = g[static_cast<std::size_t>(f.toe)].translation;
    ball_world = Vec3(t.x(), 0.0, t.z());
  } else if (skel.has_end_site[static_cast<std::size_t>(f.ankle)]) {
    const Vec3 t = a.apply(skel.end_sites[static_cast<std::size_t>(f.ankle)]);
    ball_world = Vec3(t.x(), 0.0, t.z());
  }
  f.ball_local = a.rotation.conjugate() * (ball_world - a.translation);
  return f;
}

// Lowest point of the feet (ankles, toes and their end sites), model space.
double lowest_foot_point(const Skeleton& skel, ConstPoseRef pose) {
  std::vector<Transform> g(static_cast<std::size_t>(skel.joint_count()));
  forward_kinematics(skel, pose, g);
  double lo = 1e9;
  for (Role r : {Role::LeftAnkle, Role::RightAnkle, Role::LeftToe, Role::RightToe}) {
    const int j = skel.roles[r];
    if (j < 0) continue;
    lo = std::min(lo, g[static_cast<std::size_t>(j)].translation.y());
    lo = std::min(lo, end_site_position(skel, g, j).y());
  }
  return lo;
}

// The root offset of key pose k: as authored, or with the height that puts
// the lowest foot point (heel, ball, toe tip) of either foot of `pose` on
// the floor.
Vec3 floor_offset(const CycleModel& m, const KeyPose& k, Pose& pose) {
  Vec3 off = k.root_offset.value_or(Vec3::Zero());
  if (!k.height_on_floor) return off;
  pose.translations[0] = Vec3(off.x(), 0.0, off.z());
  std::vector<Transform> g(static_cast<std::size_t>(m.skeleton.joint_count()));
  forward_kinematics(m.skeleton, pose, g);
  double lo = 1e9;
  for (const FootPivots* f : {&m.left, &m.right}) {
    const Transform& a = g[static_cast<std::size_t>(f->ankle)];
    lo = std::min({lo, a.apply(f->heel_local).y(), a.apply(f->ball_local).y()});
    if (f->toe >= 0) lo = std::min(lo, end_site_position(m.skeleton, g, f->toe).y());
  }
  off.y() = -lo - m.stand_height;
  return off;
}

// Rotations of an in-between: its own where given, else the cycle's spline
// (which at this point holds every rotation channel).
void sample_cycle_rotations_only(const CycleModel& m, const Inbetween& ib, const std::vector<double>& shift, Pose& p) {
  for (int j = 0; j < m.skeleton.joint_count(); ++j) {
    const auto& c = m.rotation[static_cast<std::size_t>(j)];
    const Quat* q = ib.pose.find(j);
    p.rotations[static_cast<std::size_t>(j)] = q ? *q : Quat(c.ref * rotation_exp(eval_channel(m, c, wrap(ib.frame + shift[static_cast<std::size_t>(j)], m.frames_per_cycle))));
  }
}

// The floor lift: how far the root must rise so that no foot point goes below
// the floor, sampled 4 times per frame, then covered by a smooth bump (sums of
// Gaussians of sigma = 0.6 frame, added until every sample is covered) and
// stored as one more periodic spline - a smooth lift, not a clamp that would
// kink the motion.
void add_floor_lift(CycleModel& m) {
  constexpr int kPerFrame = 4, kReach = 8;
  constexpr double kSigma = 2.5;  // samples (0.6 frame)
  const int n = m.frames_per_cycle * kPerFrame;
  Pose p(m.skeleton);
  std::vector<double> lift(static_cast<std::size_t>(n)), cover(static_cast<std::size_t>(n), 0.0), rest(lift.size());
  double worst = 0;
  for (int i = 0; i < n; ++i) {
    sample_cycle(m, static_cast<double>(i) / kPerFrame, p.ref());
    lift[static_cast<std::size_t>(i)] = std::max(0.0, -lowest_foot_height(m, p));
    worst = std::max(worst, lift[static_cast<std::size_t>(i)]);
  }
  if (worst <= 0) return;
  double weights[2 * kReach + 1], sum = 0;
  for (int k = -kReach; k <= kReach; ++k) sum += weights[k + kReach] = std::exp(-0.5 * (k * k) / (kSigma * kSigma));
  for (double& w : weights) w /= sum;
  auto wrap_index = [&](int i) { return static_cast<std::size_t>(((i % n) + n) % n); };
  for (int iter = 0; iter < 60; ++iter) {
    double left = 0;
    for (int i = 0; i < n; ++i) {
      rest[static_cast<std::size_t>(i)] = std::max(0.0, lift[static_cast<std::size_t>(i)] - cover[static_cast<std::size_t>(i)]);
      left = std::max(left, rest[static_cast<std::size_t>(i)]);
    }
    if (left < 1e-5) break;  // every sample covered to 0.01 mm
    // Add the blurred shortfall, scaled up so a narrow dip is covered fast.
    for (int i = 0; i < n; ++i) {
      double v = 0;
      for (int k = -kReach; k <= kReach; ++k) v += weights[k + kReach] * rest[wrap_index(i + k)];
      cover[static_cast<std::size_t>(i)] += 1.2 * v;
    }
  }
  std::vector<Entry> e;
  for (int i = 0; i < n; ++i)
    e.push_back({static_cast<double>(i) / kPerFrame, Quat::Identity(), Vec3(0, cover[static_cast<std::size_t>(i)], 0)});
  m.floor_lift = add_channel(m, std::move(e), false);
}

// Standing pose: authored, or the symmetric mean of the cycle's eight keys.
Pose standing_pose(const Skeleton& skel, const WalkKeys& keys, const std::array<Pose, kKeyCount>& step1) {
  if (keys.stand) return full_pose(skel, *keys.stand);
  Pose stand(skel);
  for (int j = 0; j < skel.joint_count(); ++j) {
    Eigen::Vector4d sum = Eigen::Vector4d::Zero();
    for (const auto& p : step1) {
      sum += positive_w(p.rotations[static_cast<std::size_t>(j)]).coeffs();
      sum += positive_w(mirror_rotation(p.rotations[static_cast<std::size_t>(skel.mirror[static_cast<std::size_t>(j)])])).coeffs();
    }
    stand.rotations[static_cast<std::size_t>(j)] = Quat(sum / sum.norm());
  }
  return stand;
}

// The root offset channel: the keys' offsets and the in-betweens' (step 2
// mirrored), delayed by the root's shift.
CycleModel::Channel root_channel(CycleModel& m, const WalkKeys& keys, const std::array<Vec3, kKeyCount>& offsets,
                                 const std::vector<double>& shift) {
  const double half = m.half_cycle();
  const double d = shift[0];
  std::vector<Entry> e;
  for (int i = 0; i < kKeyCount; ++i) {
    const Vec3 off = offsets[static_cast<std::size_t>(i)];
    e.push_back({keys.key_frames[static_cast<std::size_t>(i)] + d, Quat::Identity(), off});
    e.push_back({keys.key_frames[static_cast<std::size_t>(i)] + d + half, Quat::Identity(), mirror_vector(off)});
  }
  for (const auto& ib : keys.inbetweens)
    if (ib.pose.root_offset) {
      // An in-between's "floor" height is measured on its pose with the
      // joints it leaves out taken from the spline.
      Pose p(m.skeleton);
      sample_cycle_rotations_only(m, ib, shift, p);
      const Vec3 off = floor_offset(m, ib.pose, p);
      e.push_back({ib.frame + d, Quat::Identity(), off});
      e.push_back({ib.frame + d + half, Quat::Identity(), mirror_vector(off)});
    }
  return add_channel(m, std::move(e), false);
}

// The sampling shortcuts (results equal to the bit to evaluating every
// channel on its own): channels with the same key times share one segment
// lookup, and a rotation channel whose keys and slopes are all +0 (or that
// has one key) is the same rotation at any time, computed once.
void share_lookups(CycleModel& m) {
  auto same_times = [&](const CycleModel::TimeGroup& g, const CycleModel::Channel& c) {
    return g.count == c.count && std::equal(m.key_time.begin() + g.first, m.key_time.begin() + g.first + g.count,
                                            m.key_time.begin() + c.first);
  };
  auto group = [&](CycleModel::Channel& c) {
    c.times = -1;
    if (c.count < 2) return;
    for (std::size_t g = 0; g < m.time_groups.size(); ++g)
      if (same_times(m.time_groups[g], c)) return void(c.times = static_cast<int>(g));
    if (static_cast<int>(m.time_groups.size()) == CycleModel::max_time_groups) return;
    c.times = static_cast<int>(m.time_groups.size());
    m.time_groups.push_back({c.first, c.count});
  };
  auto positive_zero = [](const Vec3& v) { return v.x() == 0 && v.y() == 0 && v.z() == 0; };
  m.time_groups.clear();
  for (auto& c : m.rotation) {
    c.fixed = c.count == 1;
    for (int k = 0; k < c.count && !c.fixed; ++k) {
      const auto i = static_cast<std::size_t>(c.first + k);
      if (!positive_zero(m.key_value[i]) || !positive_zero(m.key_slope[i])) break;
      if (k + 1 == c.count) c.fixed = true;
    }
    c.value = c.ref * rotation_exp(eval_channel(m, c, 0.0));
    if (!c.fixed) group(c);
  }
  group(m.root_offset);
  group(m.floor_lift);
}

}  // namespace

CycleModel build_cycle(const Skeleton& skel, const WalkKeys& keys) {
  for (Role r : {Role::Pelvis, Role::LeftHip, Role::LeftKnee, Role::LeftAnkle, Role::RightHip, Role::RightKnee,
                 Role::RightAnkle})
    if (!skel.roles.has(r))
      throw Error("walk cycle: the skeleton has no joint for role '" + std::string(role_name(r)) + "'");
  if (skel.mirror.size() != static_cast<std::size_t>(skel.joint_count()))
    throw Error("walk cycle: the skeleton's left/right pairs are not resolved");
  if (keys.frames_per_cycle < 8 || keys.frames_per_cycle % 2)
    throw Error("walk cycle: frames per cycle must be even and at least 8 (got " +
                std::to_string(keys.frames_per_cycle) + ")");
  CycleModel m;
  m.skeleton = skel;
  m.frames_per_cycle = keys.frames_per_cycle;
  m.fps = keys.fps;
  m.key_frames = keys.key_frames;
  m.floor_clamp = false;  // while building: the channels are not complete yet
  const int n = skel.joint_count();
  const double half = m.half_cycle();
  const auto mir = [&](int j) { return skel.mirror[static_cast<std::size_t>(j)]; };

  // Per-joint delay; a mirrored joint inherits its counterpart's unless given.
  std::vector<double> shift(static_cast<std::size_t>(n), 0.0);
  std::vector<char> given(static_cast<std::size_t>(n), 0);
  for (auto [j, d] : keys.shift) shift[static_cast<std::size_t>(j)] = d, given[static_cast<std::size_t>(j)] = 1;
  for (auto [j, d] : keys.shift)
    if (!given[static_cast<std::size_t>(mir(j))]) shift[static_cast<std::size_t>(mir(j))] = d;

  // Full key poses (rest where unspecified) for both steps.
  std::array<Pose, kKeyCount> step1;
  for (int i = 0; i < kKeyCount; ++i) step1[static_cast<std::size_t>(i)] = full_pose(skel, keys.keys[static_cast<std::size_t>(i)]);

  m.stand = standing_pose(skel, keys, step1);
  m.stand.translations[0] = Vec3::Zero();
  m.stand_height = -lowest_foot_point(skel, m.stand);
  m.stand.translations[0] = Vec3(0, m.stand_height, 0);
  m.left = make_foot(skel, m.stand, Role::LeftAnkle, Role::LeftToe);
  m.right = make_foot(skel, m.stand, Role::RightAnkle, Role::RightToe);

  // Root offsets; "floor" heights put the pose's lowest foot point on the floor.
  std::array<Vec3, kKeyCount> offsets;
  for (int i = 0; i < kKeyCount; ++i) {
    const KeyPose& k = keys.keys[static_cast<std::size_t>(i)];
    Pose& p = step1[static_cast<std::size_t>(i)];
    offsets[static_cast<std::size_t>(i)] = floor_offset(m, k, p);
    p.translations[0] = Vec3(0, m.stand_height, 0) + offsets[static_cast<std::size_t>(i)];
    m.step_keys[static_cast<std::size_t>(i)] = p;
  }
  m.step_keys[kKeyCount] = Pose(skel);
  mirror_pose(skel, step1[0], m.step_keys[kKeyCount].ref());

  // Rotation channels: step 1 keys and in-betweens of j, then step 2 from
  // the mirrored counterpart, all delayed by j's shift.
  m.rotation.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const double d = shift[static_cast<std::size_t>(j)];
    std::vector<Entry> e;
    for (int i = 0; i < kKeyCount; ++i) {
      const double t = keys.key_frames[static_cast<std::size_t>(i)] + d;
      e.push_back({t, step1[static_cast<std::size_t>(i)].rotations[static_cast<std::size_t>(j)], Vec3::Zero()});
      e.push_back({t + half, mirror_rotation(step1[static_cast<std::size_t>(i)].rotations[static_cast<std::size_t>(mir(j))]),
                   Vec3::Zero()});
    }
    for (const auto& ib : keys.inbetweens) {
      if (const Quat* q = ib.pose.find(j)) e.push_back({ib.frame + d, *q, Vec3::Zero()});
      if (const Quat* q = ib.pose.find(mir(j))) e.push_back({ib.frame + d + half, mirror_rotation(*q), Vec3::Zero()});
    }
    m.rotation[static_cast<std::size_t>(j)] = add_channel(m, std::move(e), true);
  }
  m.root_offset = root_channel(m, keys, offsets, shift);
  if (keys.floor_clamp) add_floor_lift(m);
  m.floor_clamp = keys.floor_clamp;
  share_lookups(m);
  m.step_travel = straight_pivot_travel(m, 8).back().norm() / 2.0;
  return m;
}

void sample_cycle(const CycleModel& m, double frame, PoseRef out) {
  const double t = wrap(frame, m.frames_per_cycle);
  std::array<Segment, CycleModel::max_time_groups> segments;
  for (std::size_t g = 0; g < m.time_groups.size(); ++g)
    segments[g] = locate(m.key_time.data() + m.time_groups[g].first, m.time_groups[g].count, m.frames_per_cycle, t);
  auto value = [&](const CycleModel::Channel& c) {
    return c.times >= 0 ? blend(m, c, segments[static_cast<std::size_t>(c.times)]) : eval_channel(m, c, t);
  };
  const int n = m.skeleton.joint_count();
  for (int j = 0; j < n; ++j) {
    const auto& c = m.rotation[static_cast<std::size_t>(j)];
    out.rotations[static_cast<std::size_t>(j)] = c.fixed ? c.value : c.ref * rotation_exp(value(c));
    out.translations[static_cast<std::size_t>(j)] = m.skeleton.rest_offsets[static_cast<std::size_t>(j)];
  }
  out.translations[0] = Vec3(0, m.stand_height, 0) + value(m.root_offset);
  if (m.floor_clamp && m.floor_lift.count > 0) out.translations[0] += value(m.floor_lift);
}

double lowest_foot_height(const CycleModel& m, ConstPoseRef pose) {
  double lo = 1e300;
  for (const FootPivots* f : {&m.left, &m.right}) {
    Quat r = Quat::Identity();
    Vec3 t = Vec3::Zero();
    for (int i = 0; i < f->chain_length; ++i) {
      const auto j = static_cast<std::size_t>(f->chain[static_cast<std::size_t>(i)]);
      t = r * pose.translations[j] + t;
      r = r * pose.rotations[j];
    }
    lo = std::min({lo, (r * f->heel_local + t).y(), (r * f->ball_local + t).y()});
    if (f->toe >= 0) {
      const auto tj = static_cast<std::size_t>(f->toe);
      const Vec3 toe = r * pose.translations[tj] + t;
      lo = std::min(lo, toe.y());
      if (m.skeleton.has_end_site[tj]) lo = std::min(lo, (r * pose.rotations[tj] * m.skeleton.end_sites[tj] + toe).y());
    }
  }
  return lo;
}


Motion bake_cycle(const CycleModel& m) {
  Motion out(m.skeleton, m.fps, m.frames_per_cycle);
  for (int f = 0; f < m.frames_per_cycle; ++f) sample_cycle(m, f, out.frame(f));
  return out;
}

std::array<Vec3, 2> heel_and_ball(const CycleModel& m, ConstPoseRef pose, bool left_foot) {
  const FootPivots& f = m.foot(left_foot);
  Quat r = Quat::Identity();
  Vec3 t = Vec3::Zero();
  for (int i = 0; i < f.chain_length; ++i) {
    const auto j = static_cast<std::size_t>(f.chain[static_cast<std::size_t>(i)]);
    t = r * pose.translations[j] + t;
    r = r * pose.rotations[j];
  }
  return {r * f.heel_local + t, r * f.ball_local + t};
}

std::vector<Vec3> straight_pivot_travel(const CycleModel& m, int samples_per_frame) {
  const int n = m.frames_per_cycle * samples_per_frame;
  std::vector<Vec3> o(static_cast<std::size_t>(n) + 1, Vec3::Zero());
  Pose pose(m.skeleton);
  auto points = [&](std::array<Vec3, 4>& p) {  // [right heel, right ball, left heel, left ball]
    const auto r = heel_and_ball(m, pose.ref(), false), l = heel_and_ball(m, pose.ref(), true);
    p = {r[0], r[1], l[0], l[1]};
  };
  std::array<Vec3, 4> prev, cur;
  sample_cycle(m, 0.0, pose.ref());
  points(prev);
  for (int i = 1; i <= n; ++i) {
    const double t = static_cast<double>(i) / samples_per_frame;
    sample_cycle(m, t, pose.ref());
    points(cur);
    const StanceAt s = stance_at(m, t - 0.5 / samples_per_frame);
    const auto k = static_cast<std::size_t>((s.left ? 2 : 0) + (s.pivot == Pivot::Ball ? 1 : 0));
    o[static_cast<std::size_t>(i)] = horizontal(prev[k] + o[static_cast<std::size_t>(i) - 1] - cur[k]);
    prev = cur;
  }
  return o;
}

Vec3 foot_point(const CycleModel& m, ConstPoseRef pose, bool left_foot, Pivot which) {
  return heel_and_ball(m, pose, left_foot)[which == Pivot::Heel ? 0 : 1];
}

StanceAt stance_at(const CycleModel& m, double frame) {
  const double half = m.half_cycle();
  StanceAt s;
  s.step = static_cast<int>(std::floor(frame / half));
  const double u = frame - s.step * half;
  s.left = (s.step % 2) == 0;
  s.pivot = u < m.key_frames[2] ? Pivot::Heel : Pivot::Ball;
  return s;
}

}  // namespace legwork::walkcycle
