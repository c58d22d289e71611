// Per-frame accentuation (CoolMoves 3.1.3-3.1.4). No allocation, no exceptions in update().
#include <legwork/accent/accent.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/limits.hpp>
#include <legwork/core/rotation.hpp>
#include <legwork/ik/two_bone.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <type_traits>

namespace legwork::accent {
namespace {

// Swing-twist clamp of a local rotation about the bone axis (limits and their
// half angles' cosines as in Model::Limit).
Quat clamp_rotation(const Quat& q, const Model::Limit& l) {
  const Vec3& axis = l.axis;
  const Vec3 v(q.x(), q.y(), q.z());
  const Vec3 p = axis * v.dot(axis);
  Quat twist(q.w(), p.x(), p.y(), p.z());
  if (twist.norm() < 1e-9) twist = Quat::Identity();
  twist.normalize();
  Quat swing = q * twist.conjugate();
  auto limit = [](Quat r, double max_angle, double cos_half_max) {
    if (r.w() < 0) r.coeffs() = -r.coeffs();
    if (r.w() >= cos_half_max) return r;  // within the limit: its angle is at most max_angle
    const double angle = 2.0 * std::acos(std::clamp(r.w(), -1.0, 1.0));
    if (angle <= max_angle || angle < 1e-9) return r;
    return Quat::Identity().slerp(max_angle / angle, r);
  };
  if (l.swing > 0) swing = limit(swing, l.swing, l.cos_half_swing);
  if (l.twist > 0) twist = limit(twist, l.twist, l.cos_half_twist);
  return (swing * twist).normalized();
}

}  // namespace

const char* status_name(MatchStatus s) {
  switch (s) {
    case MatchStatus::Matched: return "matched";
    case MatchStatus::Partial: return "partial";
    case MatchStatus::Unmatched: return "unmatched";
    case MatchStatus::TrackingLost: return "tracking-lost";
    case MatchStatus::Rejected: return "rejected";
  }
  return "?";
}

// ---- Model ------------------------------------------------------------------

namespace {

void check_settings(const Database& db, const Settings& cfg) {
  const auto& r = db.skeleton().roles;
  for (Role need : {Role::Head, Role::LeftHand, Role::RightHand, Role::Pelvis})
    if (!r.has(need)) throw Error("accent: the database skeleton has no " + std::string(role_name(need)) + " joint");
  if (cfg.k_left < 0 || cfg.k_right < 0 || cfg.k_left > kMaxK || cfg.k_right > kMaxK)
    throw Error("accent: k must be between 0 and " + std::to_string(kMaxK));
  if (!(cfg.exaggeration > 0) || !std::isfinite(cfg.exaggeration)) throw Error("accent: exaggeration must be positive");
  if (!(cfg.user_height == 0 || (cfg.user_height >= kMinUserHeight && cfg.user_height <= kMaxUserHeight))) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "accent: user height %g m is outside the plausible range [%g, %g] m (0 = the database skeleton's height)",
                  cfg.user_height, kMinUserHeight, kMaxUserHeight);
    throw Error(msg);
  }
  if (!(cfg.smooth_halflife >= 0) || !std::isfinite(cfg.smooth_halflife))
    throw Error("accent: smoothing half-life must be >= 0 seconds");
  if (!std::isfinite(cfg.lying_root_smoothing) || cfg.lying_root_smoothing < 1 || cfg.lying_root_smoothing > 20)
    throw Error("accent: lying_root_smoothing must be between 1 and 20 (times the root's smoothing half-life for a lying user; 1 = off)");
  if (!std::isfinite(cfg.other_class_cost) || (cfg.other_class_cost != 0 && cfg.other_class_cost < 1) || cfg.other_class_cost > 1e6)
    throw Error("accent: other_class_cost must be 0 (search only the classes to match) or a factor from 1 to 1e6 (other classes' distances multiplied by it)");
  if (!std::isfinite(cfg.search_interval) || cfg.search_interval < 0 || cfg.search_interval > 1)
    throw Error("accent: search_interval must be between 0 and 1 second (0 = search every frame)");
  if (!std::isfinite(cfg.lying_crown) || cfg.lying_crown < 0 || cfg.lying_crown > 1)
    throw Error("accent: lying_crown must be between 0 and 1 (the share of a lying user's candidate turn taken from the headset: yaw from its crown, roll from its face; 0 = off)");
  if (!std::isfinite(cfg.smooth_feedforward) || cfg.smooth_feedforward < 0 || cfg.smooth_feedforward > 1)
    throw Error("accent: smooth_feedforward must be between 0 and 1 (the share of the candidates' motion played forward; 0 = off)");
  if (!std::isfinite(cfg.fallback_seconds) || cfg.fallback_seconds < 0)
    throw Error("accent: fallback_seconds must be >= 0");
  if (!std::isfinite(cfg.hand_ik) || cfg.hand_ik < 0 || cfg.hand_ik > 1) throw Error("accent: hand_ik must be in [0, 1]");
  if (!(cfg.contact_off >= 0 && cfg.contact_off <= cfg.contact_on && cfg.contact_on <= 1))
    throw Error("accent: foot contact thresholds need 0 <= contact_off <= contact_on <= 1");
  if (!std::isfinite(cfg.foot_release_seconds) || cfg.foot_release_seconds < 0)
    throw Error("accent: foot_release_seconds must be >= 0");
  if (!std::isfinite(cfg.foot_lift_height) || cfg.foot_lift_height < 0 || cfg.foot_lift_height > 0.5)
    throw Error("accent: foot_lift_height must be between 0 and 0.5 metres");
  if (!std::isfinite(cfg.foot_lock_follow_seconds) || cfg.foot_lock_follow_seconds < 0 || cfg.foot_lock_follow_seconds > 10)
    throw Error("accent: foot_lock_follow_seconds must be between 0 and 10 s (0 = a planted foot is held still)");
  if (!std::isfinite(cfg.foot_lock_hold_seconds) || cfg.foot_lock_hold_seconds < 0 || cfg.foot_lock_hold_seconds > 10)
    throw Error("accent: foot_lock_hold_seconds must be between 0 and 10 s (how long a planted foot stays put before it creeps)");
  if (!std::isfinite(cfg.foot_lock_slack) || cfg.foot_lock_slack < 0 || cfg.foot_lock_slack > 1)
    throw Error("accent: foot_lock_slack must be between 0 and 1 metre");
  if (!std::isfinite(cfg.foot_swing_speed) || cfg.foot_swing_speed < 0 || cfg.foot_swing_speed > 10)
    throw Error("accent: foot_swing_speed must be between 0 and 10 m/s");
  if (!std::isfinite(cfg.floor_height) || cfg.floor_height < -10 || cfg.floor_height > 10)
    throw Error("accent: floor_height must be between -10 and 10 metres");
  if (!(cfg.ik_blend_min >= 0 && cfg.ik_blend_min <= cfg.ik_blend_max && cfg.ik_blend_max <= 1))
    throw Error("accent: IK blend shares need 0 <= ik_blend_min <= ik_blend_max <= 1");
  if (!(cfg.class_seconds >= 0) || !(cfg.class_hold_seconds >= 0) || !(cfg.class_margin >= 0 && cfg.class_margin < 1) ||
      !std::isfinite(cfg.class_seconds) || !std::isfinite(cfg.class_hold_seconds))
    throw Error("accent: class recognition needs class_seconds >= 0, class_hold_seconds >= 0 and 0 <= class_margin < 1");
  if (!std::isfinite(cfg.travel_weight) || cfg.travel_weight < 0 || cfg.travel_weight > 100)
    throw Error("accent: travel_weight must be between 0 and 100 (0 = off)");
  if (!std::isfinite(cfg.max_head_height_diff) || cfg.max_head_height_diff < 0 || cfg.max_head_height_diff > 2)
    throw Error("accent: max_head_height_diff must be between 0 and 2 (a share of the body's height; 0 = off)");
  if (!(cfg.ik_blend_near < cfg.ik_blend_far) || !std::isfinite(cfg.ik_blend_far) || !(cfg.ik_blend_seconds >= 0))
    throw Error("accent: IK blend needs ik_blend_near < ik_blend_far and ik_blend_seconds >= 0");
}

std::vector<unsigned char> make_class_mask(const Database& db, const std::vector<std::string>& classes) {
  std::vector<unsigned char> mask(static_cast<std::size_t>(db.class_count()), classes.empty() ? 1 : 0);
  for (const auto& c : classes) {
    const int i = db.find_class(c);
    if (i < 0) {
      std::string list;
      for (const auto& k : db.classes()) list += (list.empty() ? "" : ", ") + k;
      throw Error("accent: class '" + c + "' is not in the database (it has: " + list + ")");
    }
    mask[static_cast<std::size_t>(i)] = 1;
  }
  return mask;
}

// One joint's limit (radians) with its half angles' cosines.
Model::Limit make_limit(const Vec3& axis, double swing, double twist) {
  return {axis, swing, twist, std::cos(0.5 * swing), std::cos(0.5 * twist)};
}

// Joint limits per joint type (swing from the rest pose, twist about the bone), degrees.
std::vector<Model::Limit> make_limits(const Skeleton& skel) {
  const auto& r = skel.roles;
  std::vector<Model::Limit> limit(static_cast<std::size_t>(skel.joint_count()));
  auto set = [&](Role role, double swing, double twist) {
    if (!r.has(role)) return;
    const int j = r[role];
    limit[static_cast<std::size_t>(j)] = make_limit(rest_direction(skel, j), deg2rad(swing), deg2rad(twist));
  };
  for (int j : r.spine_chain) limit[static_cast<std::size_t>(j)] = make_limit(rest_direction(skel, j), deg2rad(45), deg2rad(35));
  set(Role::Neck, 50, 60);
  set(Role::Head, 60, 80);
  for (Role c : {Role::LeftClavicle, Role::RightClavicle}) set(c, 35, 25);
  for (Role s : {Role::LeftShoulder, Role::RightShoulder}) set(s, 170, 100);
  for (Role e : {Role::LeftElbow, Role::RightElbow}) set(e, 160, 100);
  for (Role h : {Role::LeftHand, Role::RightHand}) set(h, 85, 80);
  for (Role h : {Role::LeftHip, Role::RightHip}) set(h, 125, 60);
  for (Role k : {Role::LeftKnee, Role::RightKnee}) set(k, 160, 35);
  for (Role a : {Role::LeftAnkle, Role::RightAnkle}) set(a, 65, 35);
  for (Role t : {Role::LeftToe, Role::RightToe}) set(t, 60, 15);
  return limit;
}

// Neutral standing pose: legs straight down, arms down at the sides.
Pose make_neutral(const Skeleton& skel) {
  const auto& r = skel.roles;
  Pose neutral(skel);
  auto point = [&](Role role, const Vec3& dir) {
    if (!r.has(role)) return;
    const int j = r[role];
    neutral.rotations[static_cast<std::size_t>(j)] = Quat::FromTwoVectors(rest_direction(skel, j), dir.normalized());
  };
  point(Role::LeftHip, Vec3(0, -1, 0));
  point(Role::RightHip, Vec3(0, -1, 0));
  point(Role::LeftShoulder, Vec3(0.2, -1, 0));
  point(Role::RightShoulder, Vec3(-0.2, -1, 0));
  return neutral;
}

}  // namespace

Model make_model(const Database& db, const Settings& settings) {
  check_settings(db, settings);
  Model m;
  m.db_ = &db;
  m.settings_ = settings;
  m.skeleton_ = db.skeleton();
  m.scale_ = settings.user_height > 0 && db.height() > 0 ? settings.user_height / db.height() : 1.0;
  m.skeleton_.scale(m.scale_);
  m.class_mask_ = make_class_mask(db, settings.classes);
  for (int c = 0; c < db.class_count(); ++c)
    if (m.class_mask_[static_cast<std::size_t>(c)] && db.class_range(c).second > db.class_range(c).first) m.allowed_.push_back(c);
  m.recognizes_ = settings.recognize_class && m.allowed_.size() > 1;
  const Skeleton& skel = m.skeleton_;
  const auto& r = skel.roles;
  const int n = skel.joint_count();
  // Arm groups: clavicle (or shoulder) and everything below it.
  m.group_.assign(static_cast<std::size_t>(n), Model::Body);
  auto mark = [&](Role top, Role fallback_top, Model::Group g) {
    const int t = r.has(top) ? r[top] : r[fallback_top];
    for (int j = 0; j < n; ++j)
      if (skel.is_ancestor(t, j)) m.group_[static_cast<std::size_t>(j)] = g;
  };
  mark(Role::LeftClavicle, Role::LeftShoulder, Model::LeftArm);
  mark(Role::RightClavicle, Role::RightShoulder, Model::RightArm);
  m.limit_ = make_limits(skel);
  {  // Each pose's successor in its trial: the next pose of the same trial and copy, one hop on.
    struct At { std::uint32_t trial = 0, frame = 0; std::uint8_t mirrored = 0; bool seen = false; };
    std::vector<At> at(static_cast<std::size_t>(db.pose_count()));
    for (int w = 0; w < db.window_count(); ++w) {
      const WindowSource& src = db.source(w);
      at[src.pose] = {src.trial, src.frame, src.mirrored, true};
    }
    m.next_pose_.assign(at.size(), -1);
    const auto hop = static_cast<std::uint32_t>(db.settings().hop);
    for (std::size_t p = 0; p + 1 < at.size(); ++p)
      if (at[p].seen && at[p + 1].seen && at[p + 1].trial == at[p].trial && at[p + 1].mirrored == at[p].mirrored &&
          at[p + 1].frame == at[p].frame + hop)
        m.next_pose_[p] = static_cast<int>(p + 1);
  }
  m.neutral_ = make_neutral(skel);
  m.can_lock_feet_ = true;
  for (Role need : {Role::LeftHip, Role::LeftKnee, Role::LeftAnkle, Role::RightHip, Role::RightKnee, Role::RightAnkle})
    m.can_lock_feet_ = m.can_lock_feet_ && r.has(need);
  std::vector<Vec3> rest(static_cast<std::size_t>(n));
  forward_positions(skel, Pose(skel), rest);
  auto chain_length = [&](const ik::TwoBoneChain& c) {
    auto at = [&](int j) { return rest[static_cast<std::size_t>(j)]; };
    return (at(c.mid) - at(c.root)).norm() + (at(c.end) - at(c.mid)).norm();
  };
  if (m.can_lock_feet_) {
    m.leg_ = {ik::left_leg(skel), ik::right_leg(skel)};
    for (std::size_t f = 0; f < 2; ++f) m.leg_length_[f] = chain_length(m.leg_[f]);
    for (std::size_t f = 0; f < 2; ++f) {
      const Role toe = f == 0 ? Role::LeftToe : Role::RightToe;
      m.toe_[f] = r.has(toe) && skel.is_ancestor(m.leg_[f].end, r[toe]) ? r[toe] : -1;
      // The sole: the lowest of the ankle, the toe and the toe's end site at rest.
      const auto end = static_cast<std::size_t>(m.leg_[f].end);
      double sole = rest[end].y();
      if (const int t = m.toe_[f]; t >= 0) {
        const auto tu = static_cast<std::size_t>(t);
        sole = std::min(sole, rest[tu].y());
        if (skel.has_end_site[tu]) sole = std::min(sole, rest[tu].y() + skel.end_sites[tu].y());
        m.toe_rest_[f] = rest[tu].y() - sole;
      }
      m.ankle_rest_[f] = rest[end].y() - sole;
    }
  }
  m.arm_ = {ik::left_arm(skel), ik::right_arm(skel)};
  for (std::size_t h = 0; h < 2; ++h) {
    m.arm_length_[h] = m.arm_[h].root >= 0 && m.arm_[h].mid >= 0 && m.arm_[h].end >= 0 ? chain_length(m.arm_[h]) : 0.0;
    const Role clavicle = h == 0 ? Role::LeftClavicle : Role::RightClavicle;
    m.clavicle_[h] = m.arm_length_[h] > 0 && r.has(clavicle) && skel.is_ancestor(r[clavicle], m.arm_[h].root) ? r[clavicle] : -1;
  }
  if (settings.ik_blend_max > 0) {
    try {
      ik::Settings ik_cfg;
      ik_cfg.floor_height = settings.floor_height;
      m.ik_ = std::make_shared<const ik::Model>(ik::make_model(skel, ik_cfg));
    } catch (const Error&) {
      m.ik_ = nullptr;  // a skeleton the IK cannot take: synthesis alone
    }
  }
  return m;
}

int Model::next_window(int w) const {
  const Database& db = database();
  const WindowSource& src = db.source(w);
  const int next = next_pose(static_cast<int>(src.pose));
  if (next < 0) return -1;
  // A pose's windows are consecutive, one per speed (builder.cpp): the next
  // pose's lie within two poses' worth of windows after w.
  const int last = std::min(db.window_count() - 1, w + 2 * static_cast<int>(db.settings().speeds.size()));
  for (int v = w + 1; v <= last; ++v) {
    const WindowSource& s = db.source(v);
    if (s.pose == static_cast<std::uint32_t>(next) && s.speed == src.speed) return v;
    if (s.pose > static_cast<std::uint32_t>(next)) break;
  }
  return -1;
}

std::size_t Model::bytes() const {
  const auto nj = static_cast<std::size_t>(skeleton_.joint_count());
  return sizeof(*this) + class_mask_.size() + allowed_.size() * sizeof(int) +
         next_pose_.size() * sizeof(int) +
         nj * (sizeof(Group) + sizeof(Limit) + sizeof(Quat) + sizeof(Vec3)) +
         nj * (3 * sizeof(Vec3) + sizeof(int) + 40);
}

// ---- State ------------------------------------------------------------------

State::State(const Model& model) {
  const auto n = static_cast<std::size_t>(model.skeleton().joint_count());
  smoothed = synth = direct = model.neutral();
  spring_rot.assign(n, Quat::Identity());
  spring_vel.assign(n, Vec3::Zero());
  motion_vel.assign(n, Vec3::Zero());
  blend_share.assign(2 * n, 0.0f);
  blend_ref.assign(4 * n, 0.0f);
  blend_sum.assign(4 * n, 0.0f);
  blend_sum_ahead.assign(4 * n, 0.0f);
  model_rot.resize(n);
  model_space.resize(n);
  const auto nc = static_cast<std::size_t>(model.database().class_count());
  class_cost.assign(nc, -1.0);
  class_time.assign(nc, 0.0);
  class_seed.assign(nc, {-1, -1});
  active_mask.assign(nc, 0);
  probe_mask.assign(nc, 0);
  if (model.recognizes_class() && model.settings().other_class_cost > 0) active_scale.assign(nc, 1.0f);
  if (model.ik_model()) {
    ik.emplace(*model.ik_model());
    ik_pose = model.neutral();
  }
  reset(model, *this);
}

void reset(const Model& model, State& s) {
  s.clock.reset();
  s.ring_head = -1;
  s.ring_size = 0;
  s.hand_offset = {Vec3(0.2, -0.6, 0.1) * model.scale(), Vec3(-0.2, -0.6, 0.1) * model.scale()};
  s.have_head = s.have_smoothed = s.have_spring = false;
  std::fill(s.motion_vel.begin(), s.motion_vel.end(), Vec3::Zero());
  s.fallback = 0;
  s.match_count = {0, 0};
  s.match_weight = 0;
  s.foot = {};
  s.contact = {0, 0};
  if (s.ik) ik::reset(*model.ik_model(), *s.ik);
  s.have_ik_distance = false;
  s.ik_distance = 0;
  s.ik_share = 0;
  s.laid_share = 0;
  s.active_class = s.challenger = -1;
  s.challenger_seconds = 0;
  s.probe_next = 0;
  s.next_probe = 0;
  s.class_switches = 0;
  std::fill(s.class_cost.begin(), s.class_cost.end(), -1.0);
  std::fill(s.class_seed.begin(), s.class_seed.end(), std::array<int, 2>{-1, -1});
  std::fill(s.active_mask.begin(), s.active_mask.end(), 0);
  s.since_search = 0;
  s.search_now = true;
}

std::size_t State::bytes() const {
  const auto nj = spring_rot.size();
  return sizeof(*this) + 3 * nj * (sizeof(Quat) + sizeof(Vec3)) + nj * (sizeof(Quat) + 2 * sizeof(Vec3)) +
         nj * (sizeof(Transform) + sizeof(Quat)) + 14 * nj * sizeof(float) +
         class_cost.size() * (2 * sizeof(double) + sizeof(std::array<int, 2>) + 2) + active_scale.size() * sizeof(float);
}

std::span<const Match> last_matches(const State& s, int hand) {
  const auto h = static_cast<std::size_t>(hand);
  return {s.matches[h].data(), static_cast<std::size_t>(s.match_count[h])};
}

// ---- update stages ------------------------------------------------------------

namespace {

using Sample = State::Sample;

// Smoothstep on [0, 1]: zero slope at both ends.
double smooth01(double x) { return x * x * (3 - 2 * x); }
constexpr int kRing = State::kRing;

// The live feature window of one hand at the database rate, interpolated from
// the ring of timed samples (in database space: exaggerated, unscaled).
void window_at(const Model& model, const State& st, int hand, HandWindow& out) {
  const double fps = model.database().feature_space().fps;
  const double now = st.ring[static_cast<std::size_t>(st.ring_head)].t;
  const double s = model.settings().exaggeration / model.scale();  // user space -> database space
  const auto h = static_cast<std::size_t>(hand);
  auto at = [&](int k) -> const Sample& { return st.ring[static_cast<std::size_t>((st.ring_head - k + kRing) % kRing)]; };
  for (int i = 0; i < kWindow; ++i) {
    const double t = now - window_lag(i) / fps;
    Vec3 rel = at(st.ring_size - 1).hand[h] - at(st.ring_size - 1).head;  // before the buffer: oldest
    for (int k = 0; k < st.ring_size; ++k) {
      const Sample& a = at(k);
      if (a.t <= t + 1e-9) {
        if (k == 0 || a.t >= t - 1e-9) {
          rel = a.hand[h] - a.head;
        } else {
          const Sample& b = at(k - 1);
          const double u = (t - a.t) / (b.t - a.t);
          rel = (1 - u) * (a.hand[h] - a.head) + u * (b.hand[h] - b.head);
        }
        break;
      }
    }
    out[static_cast<std::size_t>(i)] = rel * s;
  }
}

// A user whose head is at least this share of their standing height up is
// upright (standing, walking, running: 0.90-0.97 in the shared trials).
constexpr double kUprightHeadHeight = 0.8;
// ... and one whose head is at most this share up is lying (Settings::lying_root_smoothing).
constexpr double kLyingHeadHeight = 0.5;

// The user's head height over their standing height (the posture gates'
// Travel[3], the lying root's ramp): in database space, as stored per window.
double head_share(const Model& model, const Vec3& head) { return head.y() * (1.0 / model.scale()) / model.database().height(); }

// How far the user lies (0..1): 0 with the head at kUprightHeadHeight of their
// height or higher, rising smoothly to 1 at kLyingHeadHeight and below.
double lying(const Model& model, const State& st) {
  return smoothstep((kUprightHeadHeight - head_share(model, st.last_head)) / (kUprightHeadHeight - kLyingHeadHeight));
}

// A crown (head up axis) this far from vertical (horizontal length of the unit
// axis, sin 30 degrees) points along a lying body in full (Settings::lying_crown).
constexpr double kCrownLevel = 0.5;

// Posture gate: keeps (in order, at the front) the candidates whose head is
// about as upright as the user's (yaw-free test, max_head_tilt_deg) and, while
// the user is upright, not lower than the user's by more than
// max_head_height_diff of the body's height (the user's st.travel[3] against
// the window's stored Travel[3]): a lying or crouching body never goes under a
// standing user's head. While the user is lower, candidates whose head is
// higher by more than that are dropped too, unless none would be left (a
// lying swimmer's head height is partly the bench's: a nearest match a little
// higher beats the IK body's standing one). Returns the number kept.
int posture_gate(const Model& model, const State& st, std::span<Match> m) {
  const Database& db = model.database();
  const Settings& cfg = model.settings();
  const bool tilt = cfg.max_head_tilt_deg > 0;
  // |acos(up.y) - user_tilt| > limit, without an acos per candidate: acos
  // falls as up.y rises, so a candidate is tilted when its up.y lies outside
  // [cos(min(pi, user_tilt + limit)), cos(max(0, user_tilt - limit))].
  const double user_tilt = std::acos(std::clamp((st.last_head_rot * Vec3::UnitY()).y(), -1.0, 1.0));
  const double limit = deg2rad(cfg.max_head_tilt_deg);
  const double up_low = user_tilt + limit < kPi ? std::cos(user_tilt + limit) : -2.0;
  const double up_high = user_tilt - limit > 0 ? std::cos(user_tilt - limit) : 2.0;
  const float lowest = cfg.max_head_height_diff > 0 && st.travel[3] >= kUprightHeadHeight
                           ? static_cast<float>(st.travel[3] - cfg.max_head_height_diff)
                           : std::numeric_limits<float>::lowest();
  auto tilted = [&](int window) {
    const double y = db.head_up(static_cast<int>(db.source(window).pose)).y();
    return y < up_low || y > up_high;
  };
  // A lower (lying, kneeling) user: no candidate's head higher by more than the
  // gate either, unless none would be left.
  const bool lower = cfg.max_head_height_diff > 0 && st.travel[3] < kUprightHeadHeight;
  const float highest = static_cast<float>(st.travel[3] + cfg.max_head_height_diff);
  auto posed = [&](int window) { return !(tilt && tilted(window)) && db.travel(window)[3] >= lowest; };
  bool cap = false;
  if (lower)
    for (std::size_t i = 0; i < m.size() && !cap; ++i) cap = posed(m[i].window) && db.travel(m[i].window)[3] <= highest;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < m.size(); ++i)
    if (posed(m[i].window) && !(cap && db.travel(m[i].window)[3] > highest)) m[kept++] = m[i];
  return static_cast<int>(kept);
}

bool gates_posture(const Settings& cfg) { return cfg.max_head_tilt_deg > 0 || cfg.max_head_height_diff > 0; }

// The head position at input time t, interpolated from the ring (the oldest
// sample before the buffer).
Vec3 head_at(const State& st, double t) {
  auto at = [&](int k) -> const State::Sample& { return st.ring[static_cast<std::size_t>((st.ring_head - k + kRing) % kRing)]; };
  for (int k = 0; k < st.ring_size; ++k) {
    const State::Sample& a = at(k);
    if (a.t <= t + 1e-9) {
      if (k == 0 || a.t >= t - 1e-9) return a.head;
      const State::Sample& b = at(k - 1);
      const double u = (t - a.t) / (b.t - a.t);
      return (1 - u) * a.head + u * b.head;
    }
  }
  return at(st.ring_size - 1).head;
}

// The user's travel (database.hpp, Travel) from the headset's trajectory, in
// database space: displacements over the last seconds (less when the ring or
// the session is shorter) divided by the user/database height ratio.
void live_travel(const Model& model, State& st) {
  const State::Sample& now = st.ring[static_cast<std::size_t>(st.ring_head)];
  const double oldest = st.ring[static_cast<std::size_t>((st.ring_head - (st.ring_size - 1) + kRing) % kRing)].t;
  const double inv_scale = 1.0 / model.scale();
  auto velocity = [&](double seconds) -> Vec3 {
    const double t = std::max(now.t - seconds, oldest), span = now.t - t;
    return span > 1e-6 ? Vec3((now.head - head_at(st, t)) * (inv_scale / span)) : Vec3::Zero();
  };
  const Vec3 a = velocity(kTravelShort), b = velocity(kTravelLong), v = velocity(kTravelVertical);
  st.travel = {static_cast<float>(std::hypot(a.x(), a.z())), static_cast<float>(std::hypot(b.x(), b.z())),
               static_cast<float>(v.y()), static_cast<float>(head_share(model, now.head))};
}

// Gather: each hand's k nearest windows within the threshold, seeded by the
// last frame's matches. Gate: drop candidates whose head tilt differs from the
// user's. With a travel weight, 1.5 times as many are gathered (twice cost twice
// the CPU for 0.13 cm more, docs/accent.md) and the k of lowest
// hand + travel cost kept (then ordered by hand distance again, so the first
// is still the nearest by hand). Returns the number kept.
int gather_matches(const Model& model, State& st, int h, double threshold) {
  const Settings& cfg = model.settings();
  const Database& db = model.database();
  const auto hu = static_cast<std::size_t>(h);
  const int k = h == 0 ? cfg.k_left : cfg.k_right;
  auto& m = st.matches[hu];
  std::array<int, kMaxK> seeds;
  const int ns = st.match_count[hu];
  for (int i = 0; i < ns; ++i) seeds[static_cast<std::size_t>(i)] = m[static_cast<std::size_t>(i)].window;
  // With the posture gate, look further so k candidates usually survive it.
  const int k_search = gates_posture(cfg) ? std::min(kMaxK, k + std::max(3, k / 3)) : k;
  const bool travel = cfg.travel_weight > 0;
  const std::span<Match> found = travel ? std::span<Match>(st.candidates) : std::span<Match>(m);
  const int k_fetch = travel ? std::min(2 * kMaxK, k_search + k_search / 2) : k_search;
  std::span<const unsigned char> mask = st.active_class >= 0 ? std::span<const unsigned char>(st.active_mask) : model.class_mask();
  std::span<const float> class_scale;  // Settings::other_class_cost: every allowed class, the others' distances scaled
  if (!st.active_scale.empty() && st.active_class >= 0) class_scale = st.active_scale;
  int got = 0;
  if (st.search_now) {
    got = search_knn(db, h, st.live[hu], k_fetch, cfg.search, cfg.fast_eps, mask, found,
                     std::span<const int>(seeds.data(), static_cast<std::size_t>(ns)), cfg.fast_max_checks, class_scale);
  } else {  // Settings::search_interval: the last matches, continued
    std::array<int, 2 * kMaxK> cand;
    int nc = 0;
    for (int i = 0; i < ns; ++i) {
      const int w = seeds[static_cast<std::size_t>(i)];
      cand[static_cast<std::size_t>(nc++)] = w;
      if (const int next = model.next_window(w); next >= 0) cand[static_cast<std::size_t>(nc++)] = next;
    }
    got = rank_windows(db, h, st.live[hu], k_fetch, mask, std::span<const int>(cand.data(), static_cast<std::size_t>(nc)),
                       found, class_scale);
  }
  if (threshold > 0)
    while (got > 0 && found[static_cast<std::size_t>(got - 1)].distance > threshold) --got;
  if (gates_posture(cfg)) got = posture_gate(model, st, found.first(static_cast<std::size_t>(got)));
  if (!travel) return std::min(got, k);
  // Re-rank by hand distance (typical units) + weight x travel distance (spread units).
  const Travel& scale = db.travel_scale();
  const double inv_typical = 1.0 / db.typical_distance();
  for (int i = 0; i < got; ++i) {
    const Travel& c = db.travel(found[static_cast<std::size_t>(i)].window);
    float t2 = 0;
    for (std::size_t d = 0; d < kTravelDim; ++d) {
      const float x = (c[d] - st.travel[d]) * scale[d];
      t2 += x * x;
    }
    st.candidate_cost[static_cast<std::size_t>(i)] =
        static_cast<float>(found[static_cast<std::size_t>(i)].distance * inv_typical + cfg.travel_weight * std::sqrt(t2));
  }
  const int keep = std::min(got, k);
  for (int i = 0; i < keep; ++i) {  // selection of the `keep` lowest costs (got <= 64)
    int best = i;
    for (int j = i + 1; j < got; ++j)
      if (st.candidate_cost[static_cast<std::size_t>(j)] < st.candidate_cost[static_cast<std::size_t>(best)]) best = j;
    std::swap(st.candidate_cost[static_cast<std::size_t>(i)], st.candidate_cost[static_cast<std::size_t>(best)]);
    std::swap(found[static_cast<std::size_t>(i)], found[static_cast<std::size_t>(best)]);
  }
  std::sort(found.begin(), found.begin() + keep, [](const Match& a, const Match& b) { return a.distance < b.distance; });
  std::copy(found.begin(), found.begin() + keep, m.begin());
  return keep;
}

// A pose's head rotation in model space (the root's rotation included).
Quat head_rotation(const Database& db, std::span<const float> pose) {
  Quat q = Quat::Identity();
  const auto& parents = db.skeleton().parents;
  for (int j = db.skeleton().roles[Role::Head]; j >= 0; j = parents[static_cast<std::size_t>(j)]) {
    const float* r = pose.data() + 4 * static_cast<std::ptrdiff_t>(j);
    q = Quat(r[0], r[1], r[2], r[3]) * q;
  }
  return q;
}

// A lying user's turn of a candidate (Settings::lying_crown), from `yaw`, the
// hands' alignment: about y toward the yaw that points the
// candidate's crown (its head's up axis, horizontally) where the headset's
// points, then about that crown axis toward the roll that faces the
// candidate's face where the headset faces, each by `share` (0..1). Lying on
// the front or the back, the top of the head points away from the feet, so
// the yaw puts the body the right way round where the hands' alignment can
// turn it end over end (a back stroke matched against front strokes); the
// roll then lays a front stroke on its back, its left hand on the user's
// left (the hands reach their controllers).
Quat lying_turn(const Database& db, std::span<const float> pose, const Quat& head, double share, double yaw) {
  const Quat cand = head_rotation(db, pose);
  const Vec3 c = cand * Vec3::UnitY(), u = head * Vec3::UnitY();
  const double w = share * smoothstep(std::min(std::hypot(u.x(), u.z()), std::hypot(c.x(), c.z())) / kCrownLevel);
  if (w <= 0) return yaw_rotation(yaw);
  yaw += w * std::remainder(std::atan2(u.x(), u.z()) - std::atan2(c.x(), c.z()) - yaw, 2 * std::numbers::pi);
  const Quat turned = yaw_rotation(yaw) * cand;
  const Vec3 axis = (turned * Vec3::UnitY()).normalized();
  Vec3 fc = turned * Vec3::UnitZ(), fu = head * Vec3::UnitZ();  // faces, across the crown axis
  fc -= axis * axis.dot(fc);
  fu -= axis * axis.dot(fu);
  if (fc.norm() < 1e-3 || fu.norm() < 1e-3) return yaw_rotation(yaw);
  const double roll = std::atan2(axis.dot(fc.cross(fu)), fc.dot(fu));
  return Quat(Eigen::AngleAxisd(w * roll, axis)) * yaw_rotation(yaw);
}

// Align: each candidate's root rotated about y by the weighted closed-form
// alignment (for a lying user, also turned by lying_turn); weights inversely
// proportional to the match distance.
void align_matches(const Model& model, State& st, int h, double threshold, const AlignQuery& query) {
  const Database& db = model.database();
  const double typical = db.typical_distance();
  const auto hu = static_cast<std::size_t>(h);
  const auto& m = st.matches[hu];
  const int got = st.match_count[hu];
  double wsum = 0;
  const double crown_share = model.settings().lying_crown * lying(model, st);
  for (int i = 0; i < got; ++i) {
    const auto iu = static_cast<std::size_t>(i);
    const int win = m[iu].window;
    const WindowSource& src = db.source(win);
    const auto root = db.pose_rotations(static_cast<int>(src.pose));
    const int next = model.next_pose(static_cast<int>(src.pose));
    const auto after = next >= 0 ? db.pose_rotations(next) : root;
    st.pose_rot[hu][iu] = root.data();
    st.next_rot[hu][iu] = after.data();
    st.ahead[hu][iu] = next >= 0 ? db.settings().speeds[src.speed] / db.settings().hop : 0.0;
    Quat q0(root[0], root[1], root[2], root[3]), n0(after[0], after[1], after[2], after[3]);
    if (model.settings().align) {
      const Quat turn = crown_share > 0 ? lying_turn(db, root, st.last_head_rot, crown_share, align_yaw(query, db.align(win)))
                                        : align_turn(query, db.align(win));
      q0 = turn * q0;
      n0 = turn * n0;
    }
    st.root_aligned[hu][iu] = q0;
    st.root_next_aligned[hu][iu] = n0;
    const double d = m[iu].distance;
    st.weight[hu][iu] = 1.0 / (d + 1e-3 * typical);
    wsum += st.weight[hu][iu];
    st.confidence[hu][iu] = threshold > 0 ? std::max(0.0, 1.0 - d / threshold) : typical / (typical + d);
  }
  for (int i = 0; i < got; ++i) st.weight[hu][static_cast<std::size_t>(i)] /= wsum;
}

// One candidate's rotation q (and n, its rotation one database frame on) into
// a joint's two sums, with weight w on the reference's hemisphere:
//   sum += w q;  sum_ahead += w ((1 - a) q + a n), n on q's hemisphere.
template <typename Q, typename Sum>
void add_rotation(const Q& q, const Q& n, const Q& ref, typename Q::Scalar w, typename Q::Scalar a, Sum&& sum,
                  Sum&& sum_ahead) {
  const auto wq = q.dot(ref) < 0 ? -w : w;
  const auto wa = wq * a;
  sum += wq * q;
  sum_ahead += (wq - wa) * q + (n.dot(q) < 0 ? -wa : wa) * n;
}

// A quaternion (w, x, y, z) from a sum of them: normalised in double, the
// identity when the sum vanishes.
Quat normalized_sum(const Eigen::Vector4d& v) {
  const double len = v.norm();
  return len > 1e-12 ? Quat(v[0] / len, v[1] / len, v[2] / len, v[3] / len) : Quat::Identity();
}
Quat normalized_sum(const float* s) { return normalized_sum(Eigen::Vector4d(s[0], s[1], s[2], s[3])); }

// Blend the root's rotation (joint 0) over the candidates of the hands in
// `share`: their aligned rotations, in double, each on the first one's
// hemisphere; `ahead` gets the blend one database frame on.
Quat blend_root(const State& st, const double share[2], Quat& ahead) {
  Eigen::Vector4d acc = Eigen::Vector4d::Zero(), acc_ahead = Eigen::Vector4d::Zero(), ref = Eigen::Vector4d::Zero();
  bool have_ref = false;
  for (int h = 0; h < 2; ++h) {
    if (share[h] == 0) continue;
    const auto hu = static_cast<std::size_t>(h);
    for (int i = 0; i < st.match_count[hu]; ++i) {
      const auto iu = static_cast<std::size_t>(i);
      const Quat& r0 = st.root_aligned[hu][iu];
      const Quat& n0 = st.root_next_aligned[hu][iu];
      const Eigen::Vector4d q(r0.w(), r0.x(), r0.y(), r0.z()), n(n0.w(), n0.x(), n0.y(), n0.z());
      if (!have_ref) {
        ref = q;
        have_ref = true;
      }
      add_rotation(q, n, ref, share[h] * st.weight[hu][iu], st.ahead[hu][iu], acc, acc_ahead);
    }
  }
  ahead = normalized_sum(acc_ahead);
  return normalized_sum(acc);
}

// One candidate's part of the blend of `joints` joints (4 floats w, x, y, z a
// joint in every array): with w = share[j] x weight, on the reference's hemisphere,
//   sum[j] += w q[j];  sum_ahead[j] += w ((1 - a) q[j] + a n[j]), n[j] on q[j]'s.
// Four joints at a time in 4-float packets: their dot products come out of one
// transposed block of products, summed in the order Eigen's 4-float dot sums
// them, so every joint gets the same sums as from the one-joint loop below.
// Joints with no share (the other hand's arm) are skipped, four at a time where
// the packet holds no share at all.
void add_candidate(int joints, const float* q, const float* n, const float* ref, const float* share, float weight,
                   float a, float* sum, float* sum_ahead) {
  int j = 0;
#ifdef EIGEN_VECTORIZE
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wignored-attributes"  // a packet type as a template argument (PacketBlock)
  namespace ei = Eigen::internal;
  using P = ei::Packet4f;
  const P weight4 = ei::pset1<P>(weight), a4 = ei::pset1<P>(a), sign = ei::pset1<P>(-0.0f), zero = ei::pset1<P>(0.0f);
  for (; j + 4 <= joints; j += 4) {
    const P w = ei::pmul(ei::ploadu<P>(share + j), weight4);
    if (!ei::predux_any(ei::pcmp_lt(zero, ei::pabs(w)))) continue;  // no share in these four joints (the other arm)
    P qv[4], nv[4];
    ei::PacketBlock<P, 4> pq, pn;
    for (int l = 0; l < 4; ++l) {
      qv[l] = ei::ploadu<P>(q + 4 * (j + l));
      nv[l] = ei::ploadu<P>(n + 4 * (j + l));
      pq.packet[l] = ei::pmul(qv[l], ei::ploadu<P>(ref + 4 * (j + l)));
      pn.packet[l] = ei::pmul(nv[l], qv[l]);
    }
    ei::ptranspose(pq);  // packet[c]: component c's products of the four joints
    ei::ptranspose(pn);
    const P dq = ei::padd(ei::padd(pq.packet[0], pq.packet[2]), ei::padd(pq.packet[1], pq.packet[3]));
    const P dn = ei::padd(ei::padd(pn.packet[0], pn.packet[2]), ei::padd(pn.packet[1], pn.packet[3]));
    const P wq = ei::pxor(w, ei::pand(ei::pcmp_lt(dq, zero), sign));  // -w where q . ref < 0
    const P wa = ei::pmul(wq, a4);
    const P wn = ei::pxor(wa, ei::pand(ei::pcmp_lt(dn, zero), sign));
    const P wb = ei::psub(wq, wa);
    alignas(16) float wq1[4], wb1[4], wn1[4];
    ei::pstore(wq1, wq);
    ei::pstore(wb1, wb);
    ei::pstore(wn1, wn);
    for (int l = 0; l < 4; ++l) {
      float* s = sum + 4 * (j + l);
      float* t = sum_ahead + 4 * (j + l);
      ei::pstoreu(s, ei::padd(ei::ploadu<P>(s), ei::pmul(ei::pset1<P>(wq1[l]), qv[l])));
      ei::pstoreu(t, ei::padd(ei::ploadu<P>(t), ei::padd(ei::pmul(ei::pset1<P>(wb1[l]), qv[l]),
                                                        ei::pmul(ei::pset1<P>(wn1[l]), nv[l]))));
    }
  }
#pragma GCC diagnostic pop
#endif
  using Vec4 = Eigen::Vector4f;
  for (; j < joints; ++j) {
    if (share[j] == 0) continue;
    const Eigen::Map<const Vec4> qj(q + 4 * j), nj(n + 4 * j), rj(ref + 4 * j);
    add_rotation(qj, nj, rj, share[j] * weight, a, Eigen::Map<Vec4>(sum + 4 * j), Eigen::Map<Vec4>(sum_ahead + 4 * j));
  }
}

// Time constant (s) of the low-pass on the candidates' motion (smooth_feedforward):
// the blend's velocity changes at every change of candidates, and played forward
// unfiltered those steps show as jerk. 0.04-0.07 s measured flat (docs/accent.md).
constexpr double kMotionSeconds = 0.05;
// Longest step (s) the candidates' motion is played forward in one frame: after
// a gap in the input the filters catch up by pulling, not by extrapolating.
constexpr double kMotionLeadMax = 0.1;

// Blend: left-arm joints from left-hand matches, right-arm joints from
// right-hand matches, the rest from both; sets the global match weight and
// the candidates' own motion (st.motion_vel, low-passed over kMotionSeconds).
void blend_matches(const Model& model, State& st, double dt) {
  const int nl = st.match_count[0], nr = st.match_count[1];
  auto mean_conf = [&](int h) {
    const auto hu = static_cast<std::size_t>(h);
    double s = 0;
    for (int i = 0; i < st.match_count[hu]; ++i) s += st.confidence[hu][static_cast<std::size_t>(i)];
    return st.match_count[hu] ? s / st.match_count[hu] : 0.0;
  };
  const double cl = mean_conf(0), cr = mean_conf(1);
  const int n = model.skeleton().joint_count();
  const auto nu = static_cast<std::size_t>(n);
  const double fps = model.database().feature_space().fps;
  const double follow = 1.0 - std::exp(-dt / kMotionSeconds);
  // Each joint's share of each hand's candidates (left-arm joints from the
  // left hand's, right-arm joints from the right's, the rest from both), and
  // the global match weight.
  float* share_l = st.blend_share.data();
  float* share_r = share_l + nu;
  double weight_total = 0;
  double root_share[2] = {0, 0};
  for (int j = 0; j < n; ++j) {
    double share[2] = {0, 0};
    double joint_weight = 0;
    switch (model.group(j)) {
      case Model::LeftArm:
        share[nl ? 0 : 1] = 1;
        joint_weight = nl ? cl : 0.5 * cr;
        break;
      case Model::RightArm:
        share[nr ? 1 : 0] = 1;
        joint_weight = nr ? cr : 0.5 * cl;
        break;
      case Model::Body:
        if (nl && nr) share[0] = share[1] = 0.5;
        else share[nl ? 0 : 1] = 1;
        joint_weight = (nl && nr) ? 0.5 * (cl + cr) : 0.5 * (nl ? cl : cr);
        break;
    }
    weight_total += joint_weight;
    const auto ju = static_cast<std::size_t>(j);
    share_l[ju] = static_cast<float>(share[0]);
    share_r[ju] = static_cast<float>(share[1]);
    if (j == 0) root_share[0] = share[0], root_share[1] = share[1];
  }
  st.match_weight = std::clamp(weight_total / n, 0.0, 1.0);

  // The root from the aligned rotations (double); the candidates' own motion
  // is its blend one database frame on, as a rotation rate.
  Quat ahead;
  Quat now = blend_root(st, root_share, ahead);
  st.synth.rotations[0] = now;
  st.motion_vel[0] += follow * (rotation_log(ahead * now.conjugate()) * fps - st.motion_vel[0]);

  // The other joints from the database's float rotations, summed in float one
  // candidate at a time over all joints, each joint on the hemisphere of its
  // first candidate (from the first hand with a share in it).
  float* ref = st.blend_ref.data();
  float* sum = st.blend_sum.data();
  float* sum_ahead = st.blend_sum_ahead.data();
  std::fill(sum, sum + 4 * nu, 0.0f);
  std::fill(sum_ahead, sum_ahead + 4 * nu, 0.0f);
  for (std::size_t j = 1; j < nu; ++j) {
    const std::size_t h = share_l[j] != 0 ? 0 : 1;
    if (st.match_count[h] > 0) std::copy_n(st.pose_rot[h][0] + 4 * j, 4, ref + 4 * j);
  }
  for (int h = 0; h < 2; ++h) {
    const auto hu = static_cast<std::size_t>(h);
    const float* share = h == 0 ? share_l : share_r;
    for (int i = 0; i < st.match_count[hu]; ++i) {
      const auto iu = static_cast<std::size_t>(i);
      add_candidate(n - 1, st.pose_rot[hu][iu] + 4, st.next_rot[hu][iu] + 4, ref + 4, share + 1,
                    static_cast<float>(st.weight[hu][iu]), static_cast<float>(st.ahead[hu][iu]), sum + 4, sum_ahead + 4);
    }
  }
  for (std::size_t j = 1; j < nu; ++j) {
    now = normalized_sum(sum + 4 * j);
    ahead = normalized_sum(sum_ahead + 4 * j);
    st.synth.rotations[j] = now;
    st.motion_vel[j] += follow * (rotation_log(ahead * now.conjugate()) * fps - st.motion_vel[j]);
  }
}

// The candidates' foot contacts, blended with the weights of the body joints
// (both hands' matches, half each when both matched).
void blend_contacts(const Model& model, State& st) {
  const Database& db = model.database();
  const int nl = st.match_count[0], nr = st.match_count[1];
  const double share[2] = {nl ? (nr ? 0.5 : 1.0) : 0.0, nr ? (nl ? 0.5 : 1.0) : 0.0};
  st.contact = {0, 0};
  for (int h = 0; h < 2; ++h) {
    const auto hu = static_cast<std::size_t>(h);
    for (int i = 0; i < st.match_count[hu]; ++i) {
      const auto iu = static_cast<std::size_t>(i);
      const auto c = db.contact(static_cast<int>(db.source(st.matches[hu][iu].window).pose));
      for (std::size_t f = 0; f < 2; ++f)
        if (c[f]) st.contact[f] += share[h] * st.weight[hu][iu];
    }
  }
}

// ---- class recognition (Settings::recognize_class) ----

// A hand without a match counts this far (typical distances).
double far_cost(const Settings& cfg) { return cfg.threshold > 0 ? cfg.threshold : 10.0; }

// Folds a new cost of class c (typical distances) into its smoothed cost.
void update_class_cost(const Model& model, State& st, int c, double cost, double now) {
  const auto cu = static_cast<std::size_t>(c);
  const double tau = model.settings().class_seconds;
  if (st.class_cost[cu] < 0 || tau <= 0) {
    st.class_cost[cu] = cost;
  } else {
    const double a = 1.0 - std::exp(-std::max(0.0, now - st.class_time[cu]) / tau);
    st.class_cost[cu] += a * (cost - st.class_cost[cu]);
  }
  st.class_time[cu] = now;
}

// The check budget of a class probe. A probe walks another class's tree,
// which is cold in the cache: its cost is mostly memory misses, and the
// quarter of the frame's budget it used to get (375 checks) made a probe frame
// cost 3-4 ordinary ones (the no-class p99). On held-out boxing, running,
// walking, basketball, swimming and ladder trials (database of every class
// without them) 64 checks recognise the same class on the same share of
// frames as 375; 32 or 16 lose walking (0.74 -> 0.45) and basketball (1.0 -> 0.68).
constexpr int kProbeChecks = 64;

// Probes class c: each hand's nearest gated window in that class alone
// (seeded by the class's last best), the same search mode as the frame's.
double probe_class(const Model& model, State& st, int c) {
  const Settings& cfg = model.settings();
  const Database& db = model.database();
  const auto cu = static_cast<std::size_t>(c);
  std::fill(st.probe_mask.begin(), st.probe_mask.end(), 0);
  st.probe_mask[cu] = 1;
  const double far = far_cost(cfg), typical = db.typical_distance();
  double cost = 0;
  for (int h = 0; h < 2; ++h) {
    const auto hu = static_cast<std::size_t>(h);
    std::array<Match, 6> m;
    const int seed = st.class_seed[cu][hu];
    // A probe needs the nearest window only, seeded by the class's last best:
    // kProbeChecks full distances (fewer if the frame's budget is smaller).
    const int n = search_knn(db, h, st.live[hu], gates_posture(cfg) ? 6 : 1, cfg.search, cfg.fast_eps, st.probe_mask, m,
                             std::span<const int>(&seed, seed >= 0 ? 1 : 0),
                             cfg.fast_max_checks > 0 ? std::min(kProbeChecks, cfg.fast_max_checks) : 0);
    const int kept = gates_posture(cfg) ? posture_gate(model, st, std::span<Match>(m.data(), static_cast<std::size_t>(n))) : n;
    if (n > 0) st.class_seed[cu][hu] = m[0].window;
    cost += kept > 0 ? std::min(far, m[0].distance / typical) : far;
  }
  return cost / 2;
}

// The last frame's farthest match (typical distances, mean over the hands
// that matched), or -1 when neither did.
double kth_cost(const Model& model, const State& st) {
  const double typical = model.database().typical_distance();
  double sum = 0;
  int hands = 0;
  for (std::size_t h = 0; h < 2; ++h)
    if (st.match_count[h] > 0) {
      sum += st.matches[h][static_cast<std::size_t>(st.match_count[h] - 1)].distance / typical;
      ++hands;
    }
  return hands ? sum / hands : -1.0;
}

// How much nearer than its probed cost another class's windows may be this
// frame: a class is searched while other_class_cost x its cost < this x the
// last frame's farthest match. On the evaluation's folds (no class given),
// 1.5 kept the unpruned search's error (9.70 / 7.37 cm against 9.73 / 7.37,
// cross-subject / cross-trial) at half its extra instructions; 1 and 1.25
// cost 0.05-0.07 cm cross-subject (docs/accent.md, "Other classes pruned by
// their probes").
constexpr double kOtherClassSlack = 1.5;

// Before the frame's search: probe one class (all of them while none is
// active), then switch the active class when another has been better by the
// margin for the hold time.
void recognize_class(const Model& model, State& st, double dt) {
  const Settings& cfg = model.settings();
  const auto allowed = model.allowed_classes();
  const double now = st.ring[static_cast<std::size_t>(st.ring_head)].t;
  if (st.active_class < 0) {
    int best = allowed[0];
    for (int c : allowed) {
      update_class_cost(model, st, c, probe_class(model, st, c), now);
      if (st.class_cost[static_cast<std::size_t>(c)] < st.class_cost[static_cast<std::size_t>(best)]) best = c;
    }
    st.active_class = best;
    st.next_probe = now;
  } else {
    if (now >= st.next_probe) {
      // Each other class about twice per smoothing time (a probe costs about a frame's search).
      st.next_probe = now + cfg.class_seconds / (2.0 * static_cast<double>(allowed.size() - 1));
      int c = allowed[static_cast<std::size_t>(st.probe_next % static_cast<int>(allowed.size()))];
      if (c == st.active_class) c = allowed[static_cast<std::size_t>(++st.probe_next % static_cast<int>(allowed.size()))];
      ++st.probe_next;
      update_class_cost(model, st, c, probe_class(model, st, c), now);
    }
    int best = st.active_class;
    for (int k : allowed)
      if (st.class_cost[static_cast<std::size_t>(k)] >= 0 && st.class_cost[static_cast<std::size_t>(k)] < st.class_cost[static_cast<std::size_t>(best)]) best = k;
    const bool better = best != st.active_class &&
                        st.class_cost[static_cast<std::size_t>(best)] < (1.0 - cfg.class_margin) * st.class_cost[static_cast<std::size_t>(st.active_class)];
    if (!better) {
      st.challenger = -1;
      st.challenger_seconds = 0;
    } else {
      st.challenger_seconds = st.challenger == best ? st.challenger_seconds + dt : dt;
      st.challenger = best;
      if (st.challenger_seconds >= cfg.class_hold_seconds) {
        st.active_class = best;
        st.challenger = -1;
        st.challenger_seconds = 0;
        ++st.class_switches;
      }
    }
  }
  std::fill(st.active_mask.begin(), st.active_mask.end(), 0);
  st.active_mask[static_cast<std::size_t>(st.active_class)] = 1;
  if (!st.active_scale.empty()) {
    const float occ = static_cast<float>(model.settings().other_class_cost);
    std::fill(st.active_scale.begin(), st.active_scale.end(), occ);
    st.active_scale[static_cast<std::size_t>(st.active_class)] = 1.0f;
    // Another class is searched only where its nearest window (its probed,
    // smoothed cost), at the cost, could still enter the matches: nearer than
    // the last frame's farthest by kOtherClassSlack (a class not probed yet,
    // or a frame after one without matches, searches them all).
    const double bound = kth_cost(model, st);
    for (int c : allowed)
      if (c != st.active_class && (bound < 0 || st.class_cost[static_cast<std::size_t>(c)] < 0 ||
                                   occ * st.class_cost[static_cast<std::size_t>(c)] < kOtherClassSlack * bound))
        st.active_mask[static_cast<std::size_t>(c)] = 1;
  }
}

// After the frame's search: its best gated distances are the active class's cost.
void score_active_class(const Model& model, State& st) {
  const double far = far_cost(model.settings()), typical = model.database().typical_distance();
  double cost = 0;
  const Database& db = model.database();
  for (std::size_t h = 0; h < 2; ++h) {
    // The nearest match of the active class itself (with other_class_cost the
    // matches may include other classes); when all are of other classes, the
    // active class's nearest is no nearer than the last of them.
    const int n = st.match_count[h];
    int i = 0;
    while (i < n && db.source(st.matches[h][static_cast<std::size_t>(i)].window).cls != st.active_class) ++i;
    cost += n > 0 ? std::min(far, st.matches[h][static_cast<std::size_t>(std::min(i, n - 1))].distance / typical) : far;
    if (i < n) st.class_seed[static_cast<std::size_t>(st.active_class)][h] = st.matches[h][static_cast<std::size_t>(i)].window;
  }
  update_class_cost(model, st, st.active_class, cost / 2, st.ring[static_cast<std::size_t>(st.ring_head)].t);
}

// Gather, gate, align and blend the candidates of both hands into st.synth.
bool blend_candidates(const Model& model, State& st, double threshold, double dt) {
  HandWindow w[2];
  window_at(model, st, 0, w[0]);
  window_at(model, st, 1, w[1]);
  AlignXZ live_xz;
  fill_align(w[0], w[1], live_xz);
  const AlignQuery query = align_query(live_xz);
  for (int h = 0; h < 2; ++h) model.database().feature_space().project(w[h], st.live[static_cast<std::size_t>(h)]);
  if (model.settings().travel_weight > 0 || model.settings().max_head_height_diff > 0) live_travel(model, st);
  // Settings::search_interval: search when due (and always while a hand has
  // no match); class recognition runs with the searches, over the time since
  // the last one.
  const double interval = model.settings().search_interval;
  st.since_search += dt;
  st.search_now = st.since_search >= interval * (1 - 1e-6) || st.match_count[0] == 0 || st.match_count[1] == 0;
  if (st.search_now && model.recognizes_class()) recognize_class(model, st, st.since_search);
  if (st.search_now) st.since_search = 0;
  for (int h = 0; h < 2; ++h) {
    st.match_count[static_cast<std::size_t>(h)] = gather_matches(model, st, h, threshold);
    align_matches(model, st, h, threshold, query);
  }
  if (model.recognizes_class() && st.search_now) score_active_class(model, st);
  if (st.match_count[0] == 0 && st.match_count[1] == 0) return false;
  blend_matches(model, st, dt);
  blend_contacts(model, st);
  return true;
}

// How fast (m/s) a foot's floor estimate (the lowest height its synthesized
// ankle recently had) rises when the foot stays higher: a step up is found
// within a second or so, a swing (0.3-0.5 s) barely moves it.
constexpr double kFloorRelax = 0.1;
// Time constant (s) of the swing indicator, and half-life (s) of the critically
// damped spring on the swing clearance's lift (continuous velocity: no jerk).
constexpr double kSwingSeconds = 0.05;
constexpr double kClearanceHalflife = 0.04;
// How deep (metres, scaled with the user) the synthesized pose must push an
// ankle into its floor for the foot to stand on it whatever its speed: the
// default lift height (Settings::foot_lift_height), by which a swing grazing
// the floor is lifted over it; a foot pushed deeper is the body coming down
// onto it (a landing, a crouch), not a swing.
constexpr double kPressedDepth = 0.05;

// One foot's lock state for this frame: touch down, let go, creep beyond the
// slack, stay within the leg's reach. `ankle` is the synthesized ankle (world).
void update_lock(const Model& model, State& st, int f, const Transform& ankle, bool pressed, double dt) {
  const Settings& cfg = model.settings();
  State::FootLock& lock = st.foot[static_cast<std::size_t>(f)];
  const double c = st.contact[static_cast<std::size_t>(f)] * (1.0 - st.fallback);
  const bool contact = cfg.foot_lock && (pressed || c > (lock.locked ? cfg.contact_off : cfg.contact_on));
  if (contact && !lock.locked) {
    // Touch down where the foot is shown now (mid-release: between the old lock and the synthesized foot).
    const double w = smooth01(lock.weight);
    lock.position = ankle.translation + w * (lock.position - ankle.translation);
    lock.rotation = ankle.rotation.slerp(w, lock.rotation).normalized();
    lock.locked = true;
    lock.held = 0;
  }
  if (!contact) lock.locked = false;
  if (lock.locked) {
    // A planted foot stays put for foot_lock_hold_seconds and while the synthesized
    // one is within the slack; after that it creeps toward it by the distance
    // beyond (foot_lock_follow_seconds; 0 = held still) ...
    const Vec3 gap = ankle.translation - lock.position;
    const double g = gap.norm(), slack = cfg.foot_lock_slack * model.scale();
    lock.held += dt;
    if (cfg.foot_lock_follow_seconds > 0 && g > slack && lock.held > cfg.foot_lock_hold_seconds)
      lock.position += (1.0 - std::exp(-dt / cfg.foot_lock_follow_seconds)) * ((g - slack) / g) * gap;
    // ... and never further from the hip than the leg reaches (pulled along the leg: mostly up, like a heel rising).
    const Vec3 hip = st.model_space[static_cast<std::size_t>(model.leg(f).root)].translation;
    const Vec3 d = lock.position - hip;
    const double reach = 0.995 * model.leg_length(f);
    if (d.norm() > reach) lock.position = hip + d * (reach / d.norm());
  }
  const double fade = cfg.foot_release_seconds > 0 ? dt / cfg.foot_release_seconds : 1.0;
  lock.weight = lock.locked ? 1.0 : std::max(0.0, lock.weight - fade);
}

// Swing clearance (Settings::foot_swing_speed): metres to lift a free foot
// whose synthesized ankle moves fast (a swing) and whose ankle or toe would
// pass lower than foot_lift_height above its floor (the lowest height each
// recently had, never below `ankle_floor` / `toe_floor`: the play area's floor
// with Settings::floor); smoothed by a critically damped spring. `target_y` and
// `toe_y` are where the ankle and the toe (if `has_toe`) would be shown,
// `upright` 0..1 the headset's uprightness (a swimmer's feet have no floor),
// `contact` the foot's blended candidate contact, `step` the synthesized
// ankle's horizontal step since the last frame (zero on a fresh one).
double swing_clearance(const Model& model, State::FootLock& lock, const Vec3& ankle, const Vec3& step, double target_y,
                       bool has_toe, double toe_y, double ankle_floor, double toe_floor, double upright, double contact,
                       double dt) {
  const Settings& cfg = model.settings();
  // The stream's first frame (or the first after a reset): nothing has been
  // shown yet, so a foot its candidates do not put down is swinging now and is
  // lifted at once, not after the indicator and the spring ramp in (clips that
  // start mid-stride slid their swinging feet along the floor for ~0.1 s).
  const bool fresh = !lock.have_floor;
  if (fresh) {
    lock.floor = ankle.y();
    lock.toe_floor = toe_y;
    lock.previous = ankle;
    lock.have_floor = true;
    lock.swing = !lock.locked && contact < cfg.contact_off ? 1.0 : 0.0;
  }
  lock.floor = std::max(std::min(lock.floor + kFloorRelax * dt, ankle.y()), ankle_floor);
  lock.toe_floor = std::max(std::min(lock.toe_floor + kFloorRelax * dt, toe_y), toe_floor);
  lock.previous = ankle;
  if (cfg.foot_swing_speed <= 0 || !cfg.foot_lock) return 0.0;
  const bool swinging = !lock.locked && dt > 0 && step.norm() > cfg.foot_swing_speed * model.scale() * dt;
  if (!fresh) lock.swing = lock.locked ? 0.0 : lock.swing + (1.0 - std::exp(-dt / kSwingSeconds)) * ((swinging ? 1.0 : 0.0) - lock.swing);
  // Lift until the ankle and the toe are each foot_lift_height above their floors.
  const double clearance = cfg.foot_lift_height * model.scale();
  double below = lock.floor + clearance - target_y;
  if (has_toe) below = std::max(below, lock.toe_floor + clearance - toe_y);
  const double goal = upright * smooth01(std::clamp(lock.swing, 0.0, 1.0)) * std::max(0.0, below);
  if (fresh) {
    lock.lift = goal;
    lock.lift_velocity = 0;
    return std::max(0.0, goal);
  }
  const double y = 2.0 * std::log(2.0) / kClearanceHalflife, decay = std::exp(-y * dt);
  const double j0 = lock.lift - goal, j1 = lock.lift_velocity + j0 * y;
  lock.lift = decay * (j0 + j1 * dt) + goal;
  lock.lift_velocity = decay * (lock.lift_velocity - j1 * y * dt);
  return std::max(0.0, lock.lift);
}

// Foot locking (Settings::foot_lock) and the floor (Settings::floor): on the
// placed pose (st.model_space holds its world transforms), hold each planted
// ankle where it touched down; released feet travel back on a lifted arc,
// swinging feet clear the floor, no foot goes through it.
void lock_feet(const Model& model, State& st, double dt, PoseRef out) {
  const Settings& cfg = model.settings();
  const double up = (st.last_head_rot * Vec3::UnitY()).y();
  const double upright = smooth01(std::clamp((up - 0.174) / (0.5 - 0.174), 0.0, 1.0));
  // The lowest the ankle and the toe may be shown: their rest heights above the floor.
  constexpr double kNoFloor = -std::numeric_limits<double>::infinity();
  for (int f = 0; f < 2; ++f) {
    State::FootLock& lock = st.foot[static_cast<std::size_t>(f)];
    const ik::TwoBoneChain& chain = model.leg(f);
    const Transform ankle = st.model_space[static_cast<std::size_t>(chain.end)];  // synthesized
    const int toe = model.toe(f);
    const double ankle_floor = cfg.floor ? cfg.floor_height + model.ankle_rest_height(f) : kNoFloor;
    const double toe_floor = cfg.floor && toe >= 0 ? cfg.floor_height + model.toe_rest_height(f) : kNoFloor;
    // The synthesized ankle's horizontal step since the last frame (none on the
    // stream's first: nothing was shown before it).
    Vec3 step = lock.have_floor ? Vec3(ankle.translation - lock.previous) : Vec3::Zero();
    step.y() = 0;
    // A foot the synthesized pose pushes into the floor stands on it, planted as
    // if its candidates said so: when it moves slower than a swing; whatever
    // its speed while the user is bent over or lying (the headset tilted past
    // 60 degrees), where the swing clearance does not lift it in full and a fast
    // foot would slide along the floor (a swimmer standing bent over, matched to
    // kicking swimmers: docs/accent.md, "A bent-over user's feet on the floor");
    // and whatever its speed when the ankle is pushed more than kPressedDepth
    // into it: the body coming down onto its feet, where the clearance's lift
    // lags and the feet slid along the floor (a runner landing from a leap, the
    // body the IK body's: docs/accent.md, "A body coming down onto its feet").
    const bool pressed =
        (ankle.translation.y() < ankle_floor ||
         (toe >= 0 && st.model_space[static_cast<std::size_t>(toe)].translation.y() < toe_floor)) &&
        lock.have_floor && dt > 0 &&
        (upright < 1.0 || step.norm() < kDefaultSwingSpeed * model.scale() * dt ||
         ankle.translation.y() < ankle_floor - kPressedDepth * model.scale());
    update_lock(model, st, f, ankle, pressed, dt);
    const double w = smooth01(lock.weight);
    // A released foot travels from the lock to the synthesized ankle on a lifted
    // arc (sin^2: no velocity step at either end) instead of along the floor.
    const double arc = std::sin(kPi * (1.0 - lock.weight));
    ik::TwoBoneTarget target;
    target.position = ankle.translation + w * (lock.position - ankle.translation) + Vec3::UnitY() * (cfg.foot_lift_height * arc * arc);
    // The foot keeps its world orientation (the synthesized one, turned toward the
    // lock's by w): bending the knee to lift or reach does not tip the toe down.
    const Quat foot = ankle.rotation.slerp(w, lock.rotation);
    // The toe as it will be shown: its offset from the ankle turned with the foot.
    double toe_y = 0;
    if (toe >= 0) {
      const Vec3 offset = st.model_space[static_cast<std::size_t>(toe)].translation - ankle.translation;
      toe_y = target.position.y() + (foot * (ankle.rotation.conjugate() * offset)).y();
    }
    const double lift = swing_clearance(model, lock, ankle.translation, step, target.position.y(), toe >= 0, toe_y,
                                        ankle_floor, toe_floor, upright,
                                        st.contact[static_cast<std::size_t>(f)] * (1.0 - st.fallback), dt);
    // Never through the floor: the knee bends to raise the ankle and the toe to their floors.
    const double under = std::max(ankle_floor - (target.position.y() + lift), toe_floor - (toe_y + lift));
    if (lock.weight <= 0 && lift < 1e-5 && !(under > 0)) continue;
    target.position.y() += lift + std::max(0.0, under);
    target.rotation = foot;
    target.position_weight = 1.0;
    target.rotation_weight = 1.0;
    target.hint_weight = 0;  // keep the synthesized knee's bend plane
    ik::solve_two_bone(model.skeleton(), chain, target, out, st.model_space);
  }
}

// How far the direct mapping is laid flat (0..1): lying_crown times how far
// the user lies times how far the headset's crown is off vertical (in full
// from kCrownLevel).
double laid_flat(const Model& model, const State& st) {
  const double share = model.settings().lying_crown * lying(model, st);
  if (share <= 0) return 0;
  const Vec3 u = st.last_head_rot * Vec3::UnitY();
  return share * smoothstep(std::hypot(u.x(), u.z()) / kCrownLevel);
}

// The direct mapping: the neutral standing pose turned to the headset's yaw.
// For a user lying down (Settings::lying_crown, as far as the user lies and
// the headset's crown is off vertical) it is laid flat instead: its crown
// points where the headset's points horizontally and its face where the
// headset faces across that axis (up for a back stroke, down for a front
// one). A lying swimmer whose hands find no match then lies on the bench
// instead of standing through it with the head at bench height. Flat rather
// than turned with the whole headset: a swimmer's neck holds the head 20-40
// degrees up from the body, and a body turned with it sat up by as much.
void make_direct_pose(const Model& model, State& st) {
  const Pose& neutral = model.neutral();
  for (std::size_t j = 0; j < st.direct.rotations.size(); ++j) st.direct.rotations[j] = neutral.rotations[j];
  const Quat upright = yaw_rotation(yaw_of(st.last_head_rot)) * neutral.rotations[0];
  st.direct.rotations[0] = upright;
  const double w = laid_flat(model, st);
  if (w <= 0) return;
  const Vec3 u = st.last_head_rot * Vec3::UnitY();
  const Vec3 crown = Vec3(u.x(), 0, u.z()).normalized();
  Vec3 face = st.last_head_rot * Vec3::UnitZ();
  face -= crown * crown.dot(face);
  if (face.norm() < 1e-3) return;
  face.normalize();
  Eigen::Matrix3d flat;  // the head's model rotation lying flat: y along the crown, z the face
  flat.col(0) = crown.cross(face);
  flat.col(1) = crown;
  flat.col(2) = face;
  // The neutral head's model rotation (its root's included), then the root that carries it onto `flat`.
  const Skeleton& skel = model.skeleton();
  Quat head = Quat::Identity();
  for (int j = skel.roles[Role::Head]; j >= 0; j = skel.parents[static_cast<std::size_t>(j)])
    head = neutral.rotations[static_cast<std::size_t>(j)] * head;
  const Quat laid = (Quat(flat) * head.conjugate() * neutral.rotations[0]).normalized();
  st.direct.rotations[0] = upright.slerp(w, laid).normalized();
}

// Exact critically damped spring per joint toward this frame's rotation
// (closed form, so any dt gives the same curve): unlike the EWMA alone, the
// output's angular velocity stays continuous when the candidate set switches.
void spring_filter(const Model& model, State& st, double dt, PoseRef out) {
  const std::size_t n = out.rotations.size();
  if (!st.have_spring) {
    for (std::size_t j = 0; j < n; ++j) {
      st.spring_rot[j] = out.rotations[j];
      st.spring_vel[j] = Vec3::Zero();
    }
    st.have_spring = true;
    return;
  }
  const double y = 2.0 * std::log(2.0) / model.settings().smooth_halflife;  // half the damping
  const double decay = std::exp(-y * dt);
  // The candidates' motion played forward (smooth_feedforward), as far as the pose is theirs.
  const double lead = model.settings().smooth_feedforward * (1.0 - st.fallback) * (1.0 - st.ik_share - st.laid_share) * std::min(dt, kMotionLeadMax);
  // A lying user's root turns slowly (lying_root_smoothing): from a head at 0.8 of
  // the user's height down to 0.5, the root's half-life grows to that many times.
  const double root_factor = 1.0 + (model.settings().lying_root_smoothing - 1.0) * lying(model, st);
  for (std::size_t j = 0; j < n; ++j) {
    if (lead > 0) st.spring_rot[j] = (rotation_exp(st.motion_vel[j] * lead) * st.spring_rot[j]).normalized();
    const Quat& goal = out.rotations[j];
    const double yj = j == 0 ? y / root_factor : y, dj = j == 0 ? std::exp(-yj * dt) : decay;
    const Vec3 j0 = rotation_log(st.spring_rot[j] * goal.conjugate());
    const Vec3 j1 = st.spring_vel[j] + j0 * yj;
    st.spring_rot[j] = (rotation_exp(dj * (j0 + j1 * dt)) * goal).normalized();
    st.spring_vel[j] = dj * (st.spring_vel[j] - j1 * yj * dt);
    out.rotations[j] = st.spring_rot[j];
  }
}

// Head model rotation = the headset's; its local rotation follows from its parents.
void drive_head(const Model& model, State& st, const Quat& head_rotation, PoseRef out) {
  const Skeleton& skel = model.skeleton();
  const int head = skel.roles[Role::Head];
  for (int j = 0; j < head; ++j) {
    const auto ju = static_cast<std::size_t>(j);
    const int p = skel.parents[ju];
    st.model_rot[ju] = p < 0 ? out.rotations[ju] : st.model_rot[static_cast<std::size_t>(p)] * out.rotations[ju];
  }
  const int hp = skel.parents[static_cast<std::size_t>(head)];
  const Quat parent = hp >= 0 ? st.model_rot[static_cast<std::size_t>(hp)] : Quat::Identity();
  out.rotations[static_cast<std::size_t>(head)] = (parent.conjugate() * head_rotation).normalized();
}

// Most a clavicle swings (radians) to bring a wrist onto a controller the
// synthesized arm cannot reach (the IK baseline's limit).
constexpr double kClavicleReach = 0.5;

// A hand target beyond the arm's reach (the scaled database arm is often a
// little shorter than the user's, or the synthesized shoulder sits further
// away): the clavicle swings its shoulder toward the target, as the IK
// baseline's does, by `weight` of the needed angle. Updates st.model_space.
void extend_reach(const Model& model, State& st, int h, const Vec3& target, double weight, PoseRef out) {
  const Skeleton& skel = model.skeleton();
  const int c = model.clavicle(h);
  if (c < 0 || weight <= 0) return;
  auto at = [&](int j) -> const Transform& { return st.model_space[static_cast<std::size_t>(j)]; };
  const Vec3 shoulder = at(model.arm(h).root).translation;
  const double excess = (target - shoulder).norm() - 0.999 * model.arm_length(h);
  const Vec3 cp = at(c).translation;
  const Vec3 b = shoulder - cp;
  const Vec3 axis = b.cross(target - cp);
  if (excess <= 0 || b.norm() < 1e-6 || axis.norm() < 1e-9) return;
  const Quat q(Eigen::AngleAxisd(weight * std::min(kClavicleReach, 1.2 * excess / b.norm()), axis.normalized()));
  const int p = skel.parents[static_cast<std::size_t>(c)];
  const Quat cm = (q * at(c).rotation).normalized();
  out.rotations[static_cast<std::size_t>(c)] = (p < 0 ? cm : at(p).rotation.conjugate() * cm).normalized();
  forward_kinematics(skel, out, st.model_space);
}

// Hand IK: pull the wrists onto the (exaggerated) hands.
void reach_hands(const Model& model, State& st, const Quat& head_rotation, const Vec3& head_position, double ik_weight,
                 PoseRef out) {
  const Skeleton& skel = model.skeleton();
  const Quat yaw = yaw_rotation(yaw_of(head_rotation));
  for (int h = 0; h < 2; ++h) {
    const ik::TwoBoneChain& chain = model.arm(h);
    ik::TwoBoneTarget target;
    // Exaggerated hands (as matched), so the style control survives hand IK.
    target.position = head_position + model.settings().exaggeration * st.hand_offset[static_cast<std::size_t>(h)];
    extend_reach(model, st, h, target.position, std::clamp(ik_weight, 0.0, 1.0), out);
    // Elbows bend down and back, slightly outward.
    target.hint = st.model_space[static_cast<std::size_t>(chain.mid)].translation +
                  yaw * Vec3(h == 0 ? 0.3 : -0.3, -0.5, -0.4) * model.scale();
    target.position_weight = std::clamp(ik_weight, 0.0, 1.0);
    target.hint_weight = 1.0;
    ik::solve_two_bone(skel, chain, target, out, st.model_space);
  }
}

// Joint limits, head drive, placement at the headset, hand IK.
void finish_pose(const Model& model, State& st, const Quat& head_rotation, const Vec3& head_position, double ik_weight,
                 PoseRef out) {
  const Skeleton& skel = model.skeleton();
  const int n = skel.joint_count();
  if (model.settings().joint_limits)
    for (int j = 1; j < n; ++j) {
      const auto& l = model.limit(j);
      if (l.swing > 0 || l.twist > 0)
        out.rotations[static_cast<std::size_t>(j)] = clamp_rotation(out.rotations[static_cast<std::size_t>(j)], l);
    }
  if (model.settings().drive_head) drive_head(model, st, head_rotation, out);
  for (int j = 0; j < n; ++j) out.translations[static_cast<std::size_t>(j)] = skel.rest_offsets[static_cast<std::size_t>(j)];
  out.translations[0] = Vec3::Zero();
  forward_kinematics(skel, out, st.model_space);
  // Place the body so its head joint sits at the headset.
  const Vec3 shift = head_position - st.model_space[static_cast<std::size_t>(skel.roles[Role::Head])].translation;
  out.translations[0] = shift;
  for (auto& t : st.model_space) t.translation += shift;
  if (ik_weight > 1e-6) reach_hands(model, st, head_rotation, head_position, ik_weight, out);
}

// Confidence blend toward the IK body (Settings::ik_blend_*): the IK avatar
// solves the same frame; its share grows with the smoothed match distance.
// Its local rotations are slerped into `out` before the spring filter, so the
// IK body's steps are smoothed like the synthesis's switches, and before the
// placement and hand IK, so the hands end on the controllers.
void blend_ik(const Model& model, const TrackerFrame& in, State& st, double dt, PoseRef out) {
  const Settings& cfg = model.settings();
  if (ik::update(*model.ik_model(), in, *st.ik, st.ik_pose.ref()) == UpdateStatus::Rejected) return;
  const double typical = model.database().typical_distance();
  double d = 0;  // mean over the hands of the best match distance; "far" for a hand without match
  for (std::size_t h = 0; h < 2; ++h)
    d += 0.5 * (st.match_count[h] > 0 ? st.matches[h][0].distance / typical : cfg.ik_blend_far);
  if (!st.have_ik_distance) st.ik_distance = d;
  else if (cfg.ik_blend_seconds > 0) st.ik_distance += (1.0 - std::exp(-dt / cfg.ik_blend_seconds)) * (d - st.ik_distance);
  else st.ik_distance = d;
  st.have_ik_distance = true;
  const double x = std::clamp((st.ik_distance - cfg.ik_blend_near) / (cfg.ik_blend_far - cfg.ik_blend_near), 0.0, 1.0);
  const double low_confidence = cfg.ik_blend_min + (cfg.ik_blend_max - cfg.ik_blend_min) * smooth01(x);
  // The IK body stands upright: none of it for a user lying down (fading out as the head tilts 60..80 degrees,
  // and with lying_crown, which turns a lying body the right way round, as the head goes down). A lying
  // user's share goes to the direct mapping laid flat instead (make_direct_pose).
  const double up = (st.last_head_rot * Vec3::UnitY()).y();
  const double u = std::clamp((up - 0.174) / (0.5 - 0.174), 0.0, 1.0);
  const double lies = cfg.lying_crown * lying(model, st);
  st.ik_share = low_confidence * smooth01(u) * (1.0 - lies);
  st.laid_share = low_confidence * lies;
  if (st.laid_share > 0)
    for (std::size_t j = 0; j < out.rotations.size(); ++j) out.rotations[j] = slerp(out.rotations[j], st.direct.rotations[j], st.laid_share);
  if (st.ik_share <= 0) return;
  for (std::size_t j = 0; j < out.rotations.size(); ++j)
    out.rotations[j] = slerp(out.rotations[j], st.ik_pose.rotations[j], st.ik_share);
}

// Devices: hold the last good data of anything unusable. Returns true if any was lost.
bool take_devices(const Model& model, const TrackerFrame& in, State& st) {
  (void)model;
  bool lost = false;
  if (usable(in.head())) {
    st.last_head = in.head().position;
    st.last_head_rot = in.head().rotation.normalized();
    st.have_head = true;
  } else {
    lost = true;
  }
  for (int h = 0; h < 2; ++h) {
    const DevicePose& d = in.hand(h);
    if (d.valid && all_finite(d.position) && d.position.cwiseAbs().maxCoeff() <= kMaxCoordinate && st.have_head)
      st.hand_offset[static_cast<std::size_t>(h)] = d.position - st.last_head;
    else
      lost = true;
  }
  st.ring_head = (st.ring_head + 1) % kRing;
  st.ring_size = std::min(st.ring_size + 1, kRing);
  Sample& s = st.ring[static_cast<std::size_t>(st.ring_head)];
  s.t = in.time;
  s.head = st.last_head;
  s.hand = {st.last_head + st.hand_offset[0], st.last_head + st.hand_offset[1]};
  return lost;
}

bool pose_finite(ConstPoseRef p) {
  bool ok = all_finite(p.translations[0]);
  for (const auto& q : p.rotations) ok = ok && all_finite(q) && q.norm() > 1e-6;
  return ok;
}

}  // namespace

UpdateStatus update(const Model& model, const TrackerFrame& in, State& st, PoseRef out, Info* info) {
  const Settings& cfg = model.settings();
  const std::size_t nj = static_cast<std::size_t>(model.skeleton().joint_count());
  if (out.rotations.size() != nj || out.translations.size() != nj) {
    if (info) info->match = MatchStatus::Rejected;
    return UpdateStatus::Rejected;
  }
  const FrameClock::Step step = st.clock.advance(in.time);
  if (step.verdict == FrameClock::Verdict::Reject) {
    if (info) {
      info->match = MatchStatus::Rejected;
      info->match_weight = st.match_weight;
      info->fallback = st.fallback;
    }
    return UpdateStatus::Rejected;
  }
  const bool restarted = step.verdict == FrameClock::Verdict::Restart;
  if (restarted) {
    const FrameClock clock = st.clock;  // keep the restarted clock
    reset(model, st);
    st.clock = clock;
  }
  const double dt = step.dt;
  const bool lost = take_devices(model, in, st);

  const double threshold = cfg.threshold > 0 ? cfg.threshold * model.database().typical_distance() : 0.0;
  const bool matched = st.have_head && !cfg.direct_only && blend_candidates(model, st, threshold, dt);
  if (!matched) {
    st.match_count = {0, 0};
    st.contact = {0, 0};
    std::fill(st.motion_vel.begin(), st.motion_vel.end(), Vec3::Zero());
  }
  if (matched) {
    const double w = cfg.smooth && st.have_smoothed ? std::max(st.match_weight, cfg.min_smoothing_weight) : 1.0;
    const double lead = cfg.smooth_feedforward * std::min(dt, kMotionLeadMax);  // the candidates' motion played forward first
    for (std::size_t j = 0; j < nj; ++j) {
      const Quat from = lead > 0 ? Quat(rotation_exp(st.motion_vel[j] * lead) * st.smoothed.rotations[j]) : st.smoothed.rotations[j];
      st.smoothed.rotations[j] = w >= 1.0 ? st.synth.rotations[j] : slerp(from, st.synth.rotations[j], w);
    }
    st.have_smoothed = true;
  } else {
    st.match_weight = 0;
  }
  // Converge toward the direct mapping while unmatched or tracking is lost.
  const double target = (!matched || lost) ? 1.0 : 0.0;
  const double rate = cfg.fallback_seconds > 0 ? dt / cfg.fallback_seconds : 1.0;
  st.fallback += std::clamp(target - st.fallback, -rate, rate);
  if (!st.have_smoothed || cfg.direct_only) st.fallback = 1.0;
  make_direct_pose(model, st);
  for (std::size_t j = 0; j < nj; ++j)
    out.rotations[j] = st.fallback <= 0 ? st.smoothed.rotations[j]
                       : st.fallback >= 1 ? st.direct.rotations[j]
                                          : slerp(st.smoothed.rotations[j], st.direct.rotations[j], st.fallback);
  if (st.ik && !cfg.direct_only) blend_ik(model, in, st, dt, out);
  if (cfg.smooth && cfg.smooth_halflife > 0 && !cfg.direct_only) spring_filter(model, st, dt, out);
  finish_pose(model, st, st.last_head_rot, st.last_head, std::max(cfg.hand_ik, st.fallback), out);
  if ((cfg.foot_lock || cfg.floor) && model.can_lock_feet() && !cfg.direct_only) lock_feet(model, st, dt, out);
  // Never hand out a broken pose: fall back to the neutral one.
  if (!pose_finite(out)) {
    const Pose& neutral = model.neutral();
    std::copy(neutral.rotations.begin(), neutral.rotations.end(), out.rotations.begin());
    std::copy(neutral.translations.begin(), neutral.translations.end(), out.translations.begin());
    out.translations[0] = st.last_head;
  }

  const MatchStatus match = lost ? MatchStatus::TrackingLost
                            : !matched ? MatchStatus::Unmatched
                            : (st.match_count[0] == 0 || st.match_count[1] == 0) ? MatchStatus::Partial
                                                                                  : MatchStatus::Matched;
  if (info) {
    info->match = match;
    info->match_weight = st.match_weight;
    info->fallback = st.fallback;
    info->matches = st.match_count;
    for (std::size_t f = 0; f < 2; ++f) {
      info->contact[f] = static_cast<float>(st.contact[f]);
      info->foot_locked[f] = st.foot[f].locked;
    }
    info->ik_share = st.ik_share;
    info->searched = st.have_head && !cfg.direct_only && st.search_now;  // blend_candidates ran and searched
    info->active_class = st.active_class;
    info->classes_searched = !info->searched ? 0  // continued matches (Settings::search_interval)
                             : st.active_class < 0 ? static_cast<int>(model.allowed_classes().size())
                                                   : static_cast<int>(std::count(st.active_mask.begin(), st.active_mask.end(), 1));
    const double typical = model.database().typical_distance();
    for (int h = 0; h < 2; ++h)
      info->best_distance[static_cast<std::size_t>(h)] = st.match_count[static_cast<std::size_t>(h)]
          ? static_cast<float>(st.matches[static_cast<std::size_t>(h)][0].distance / typical) : 0.0f;
  }
  if (restarted) return UpdateStatus::Restarted;
  return lost ? UpdateStatus::Degraded : UpdateStatus::Ok;
}

void describe(const Info& i, InfoFields& out) {
  out.add("match", status_name(i.match));
  out.add("match_weight", i.match_weight);
  out.add("fallback", i.fallback);
  out.add("matches_left", i.matches[0]);
  out.add("matches_right", i.matches[1]);
  out.add("active_class", i.active_class);
  out.add("classes_searched", i.classes_searched);
  out.add("searched", i.searched ? 1 : 0);
}

}  // namespace legwork::accent
