// Per-frame accentuation (CoolMoves 3.1.3-3.1.4). No allocation, no exceptions in update().
#include <legwork/accent/accentuator.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>

#if LEGWORK_ACCENT_HAVE_IK
#include <legwork/ik/two_bone.hpp>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>

namespace legwork::accent {
namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }
bool finite(const Quat& q) { return std::isfinite(q.w()) && std::isfinite(q.x()) && std::isfinite(q.y()) && std::isfinite(q.z()) && q.norm() > 1e-6; }

Vec3 rest_direction(const Skeleton& s, int j) {
  Vec3 d = Vec3::Zero();
  for (int c = j + 1; c < s.joint_count(); ++c)
    if (s.parents[static_cast<std::size_t>(c)] == j) d += s.rest_offsets[static_cast<std::size_t>(c)];
  if (d.norm() < 1e-9 && s.has_end_site[static_cast<std::size_t>(j)]) d = s.end_sites[static_cast<std::size_t>(j)];
  return d.norm() < 1e-9 ? Vec3::UnitY() : Vec3(d.normalized());
}

// Swing-twist clamp of a local rotation about the bone axis.
Quat clamp_rotation(const Quat& q, const Vec3& axis, double max_swing, double max_twist) {
  const Vec3 v(q.x(), q.y(), q.z());
  const Vec3 p = axis * v.dot(axis);
  Quat twist(q.w(), p.x(), p.y(), p.z());
  if (twist.norm() < 1e-9) twist = Quat::Identity();
  twist.normalize();
  Quat swing = q * twist.conjugate();
  auto limit = [](Quat r, double max_angle) {
    if (r.w() < 0) r.coeffs() = -r.coeffs();
    const double angle = 2.0 * std::acos(std::clamp(r.w(), -1.0, 1.0));
    if (angle <= max_angle || angle < 1e-9) return r;
    return Quat::Identity().slerp(max_angle / angle, r);
  };
  if (max_swing > 0) swing = limit(swing, max_swing);
  if (max_twist > 0) twist = limit(twist, max_twist);
  return (swing * twist).normalized();
}

// Rotation vector (axis * angle) of a unit quaternion and back.
Vec3 rotation_log(Quat q) {
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Vec3 v(q.x(), q.y(), q.z());
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;
  return v * (2.0 * std::atan2(s, q.w()) / s);
}
Quat rotation_exp(const Vec3& r) {
  const double angle = r.norm();
  if (angle < 1e-12) return Quat(1.0, 0.5 * r.x(), 0.5 * r.y(), 0.5 * r.z()).normalized();
  return Quat(Eigen::AngleAxisd(angle, r / angle));
}

double yaw_of(const Quat& q) {
  const Vec3 f = q * Vec3::UnitZ();
  return std::atan2(f.x(), f.z());
}

}  // namespace

bool have_arm_ik() {
#if LEGWORK_ACCENT_HAVE_IK
  return true;
#else
  return false;
#endif
}

const char* status_name(FrameStatus s) {
  switch (s) {
    case FrameStatus::Matched: return "matched";
    case FrameStatus::Partial: return "partial";
    case FrameStatus::Unmatched: return "unmatched";
    case FrameStatus::TrackingLost: return "tracking-lost";
    case FrameStatus::Rejected: return "rejected";
  }
  return "?";
}

Accentuator::Accentuator(const Database& db, AccentConfig cfg) : db_(&db), cfg_(std::move(cfg)) {
  skel_ = db.skeleton();
  const auto& r = skel_.roles;
  for (Role need : {Role::Head, Role::LeftHand, Role::RightHand, Role::Pelvis})
    if (!r.has(need)) throw Error("accent: the database skeleton has no " + std::string(role_name(need)) + " joint");
  if (cfg_.k_left < 0 || cfg_.k_right < 0 || cfg_.k_left > kMaxK || cfg_.k_right > kMaxK)
    throw Error("accent: k must be between 0 and " + std::to_string(kMaxK));
  if (!(cfg_.exaggeration > 0)) throw Error("accent: exaggeration must be positive");
  if (cfg_.user_height < 0 || !std::isfinite(cfg_.user_height)) throw Error("accent: user height must be positive");
  scale_ = cfg_.user_height > 0 && db.height() > 0 ? cfg_.user_height / db.height() : 1.0;
  skel_.scale(scale_);
  class_mask_.assign(static_cast<std::size_t>(db.class_count()), cfg_.classes.empty() ? 1 : 0);
  for (const auto& c : cfg_.classes) {
    const int i = db.find_class(c);
    if (i < 0) {
      std::string list;
      for (const auto& k : db.classes()) list += (list.empty() ? "" : ", ") + k;
      throw Error("accent: class '" + c + "' is not in the database (it has: " + list + ")");
    }
    class_mask_[static_cast<std::size_t>(i)] = 1;
  }
  const int n = skel_.joint_count();
  const auto nu = static_cast<std::size_t>(n);
  // Arm groups: clavicle (or shoulder) and everything below it.
  group_.assign(nu, Body);
  auto mark = [&](Role top, Role fallback_top, Group g) {
    const int t = r.has(top) ? r[top] : r[fallback_top];
    for (int j = 0; j < n; ++j)
      if (skel_.is_ancestor(t, j)) group_[static_cast<std::size_t>(j)] = g;
  };
  mark(Role::LeftClavicle, Role::LeftShoulder, LeftArm);
  mark(Role::RightClavicle, Role::RightShoulder, RightArm);
  // Joint limits per joint type (swing from the rest pose, twist about the bone), degrees.
  limit_.assign(nu, Limit{});
  auto set = [&](Role role, double swing, double twist) {
    if (!r.has(role)) return;
    const int j = r[role];
    limit_[static_cast<std::size_t>(j)] = {rest_direction(skel_, j), deg2rad(swing), deg2rad(twist)};
  };
  for (int j : r.spine_chain) limit_[static_cast<std::size_t>(j)] = {rest_direction(skel_, j), deg2rad(45), deg2rad(35)};
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

  // Neutral standing pose: legs straight down, arms down at the sides.
  neutral_ = Pose(skel_);
  auto point = [&](Role role, const Vec3& dir) {
    if (!r.has(role)) return;
    const int j = r[role];
    neutral_.rotations[static_cast<std::size_t>(j)] = Quat::FromTwoVectors(rest_direction(skel_, j), dir.normalized());
  };
  point(Role::LeftHip, Vec3(0, -1, 0));
  point(Role::RightHip, Vec3(0, -1, 0));
  point(Role::LeftShoulder, Vec3(0.2, -1, 0));
  point(Role::RightShoulder, Vec3(-0.2, -1, 0));

  synth_ = smoothed_ = direct_ = out_ = neutral_;
  model_.resize(nu);
  model_rot_.resize(nu);
  spring_rot_.assign(nu, Quat::Identity());
  spring_vel_.assign(nu, Vec3::Zero());
  if (!(cfg_.smooth_halflife >= 0) || !std::isfinite(cfg_.smooth_halflife)) throw Error("accent: smoothing half-life must be >= 0 seconds");
  reset();
}

void Accentuator::reset() {
  ring_head_ = -1;
  ring_size_ = 0;
  hand_offset_ = {Vec3(0.2, -0.6, 0.1) * scale_, Vec3(-0.2, -0.6, 0.1) * scale_};
  have_head_ = started_ = have_smoothed_ = have_spring_ = false;
  last_time_ = 0;
  fallback_ = 0;
  match_count_ = {0, 0};
  match_weight_ = 0;
  out_ = neutral_;
}

std::span<const Match> Accentuator::matches(int hand) const {
  return {matches_[static_cast<std::size_t>(hand)].data(), static_cast<std::size_t>(match_count_[static_cast<std::size_t>(hand)])};
}

std::size_t Accentuator::state_bytes() const {
  const auto nj = static_cast<std::size_t>(skel_.joint_count());
  return sizeof(*this) + 5 * nj * (sizeof(Quat) + sizeof(Vec3)) + nj * (sizeof(Quat) + sizeof(Vec3)) + nj * (sizeof(Transform) + sizeof(Quat) + sizeof(Limit) + 1) +
         class_mask_.size() + skel_.joint_count() * (sizeof(Vec3) * 2 + 40);
}

void Accentuator::window_at(int hand, HandWindow& out) const {
  const double fps = db_->feature_space().fps;
  const double now = ring_[static_cast<std::size_t>(ring_head_)].t;
  const double s = cfg_.exaggeration / scale_;  // user space -> database space
  auto at = [&](int k) -> const Sample& { return ring_[static_cast<std::size_t>((ring_head_ - k + kRing) % kRing)]; };
  for (int i = 0; i < kWindow; ++i) {
    const double t = now - (kWindow - 1 - i) / fps;
    Vec3 rel = at(ring_size_ - 1).hand[static_cast<std::size_t>(hand)] - at(ring_size_ - 1).head;  // before the buffer: oldest
    for (int k = 0; k < ring_size_; ++k) {
      const Sample& a = at(k);
      if (a.t <= t + 1e-9) {
        if (k == 0 || a.t >= t - 1e-9) {
          rel = a.hand[static_cast<std::size_t>(hand)] - a.head;
        } else {
          const Sample& b = at(k - 1);
          const double u = (t - a.t) / (b.t - a.t);
          rel = (1 - u) * (a.hand[static_cast<std::size_t>(hand)] - a.head) + u * (b.hand[static_cast<std::size_t>(hand)] - b.head);
        }
        break;
      }
    }
    out[static_cast<std::size_t>(i)] = rel * s;
  }
}

bool Accentuator::blend_candidates(double threshold) {
  const Database& db = *db_;
  const double typical = db.typical_distance();
  const int n = skel_.joint_count();
  HandWindow w[2];
  window_at(0, w[0]);
  window_at(1, w[1]);
  AlignXZ query_xz;
  fill_align(w[0], w[1], query_xz);
  const int k[2] = {cfg_.k_left, cfg_.k_right};
  for (int h = 0; h < 2; ++h) {
    Feature& f = live_[static_cast<std::size_t>(h)];
    db.feature_space().project(w[h], f);
    auto& m = matches_[static_cast<std::size_t>(h)];
    // Last frame's matches seed the search (motion is continuous).
    std::array<int, kMaxK> seeds;
    const int ns = match_count_[static_cast<std::size_t>(h)];
    for (int i = 0; i < ns; ++i) seeds[static_cast<std::size_t>(i)] = m[static_cast<std::size_t>(i)].window;
    // With the head-tilt gate, look further so k candidates usually survive it.
    const int k_search = cfg_.max_head_tilt_deg > 0 ? std::min(kMaxK, k[h] + std::max(3, k[h] / 3)) : k[h];
    int got = search_knn(db, h, f, k_search, cfg_.search, cfg_.fast_eps, class_mask_, m, std::span<const int>(seeds.data(), static_cast<std::size_t>(ns)),
                         cfg_.fast_max_checks);
    if (threshold > 0)
      while (got > 0 && m[static_cast<std::size_t>(got - 1)].distance > threshold) --got;
    if (cfg_.max_head_tilt_deg > 0) {
      // Keep candidates whose head is about as upright as the user's (yaw-free test).
      const double user_tilt = std::acos(std::clamp((last_head_rot_ * Vec3::UnitY()).y(), -1.0, 1.0));
      const double limit = deg2rad(cfg_.max_head_tilt_deg);
      int kept = 0;
      for (int i = 0; i < got; ++i) {
        const Vec3 up = db.head_up(static_cast<int>(db.source(m[static_cast<std::size_t>(i)].window).pose));
        if (std::abs(std::acos(std::clamp(up.y(), -1.0, 1.0)) - user_tilt) <= limit) m[static_cast<std::size_t>(kept++)] = m[static_cast<std::size_t>(i)];
      }
      got = std::min(kept, k[h]);
    }
    match_count_[static_cast<std::size_t>(h)] = got;
    double wsum = 0;
    for (int i = 0; i < got; ++i) {
      const auto iu = static_cast<std::size_t>(i);
      const int win = m[iu].window;
      const auto root = db.pose_rotations(static_cast<int>(db.source(win).pose));
      pose_rot_[static_cast<std::size_t>(h)][iu] = root.data();
      Quat q0(root[0], root[1], root[2], root[3]);
      if (cfg_.align) q0 = Quat(Eigen::AngleAxisd(align_yaw(query_xz, db.align(win)), Vec3::UnitY())) * q0;
      root_aligned_[static_cast<std::size_t>(h)][iu] = q0;
      const double d = m[iu].distance;
      weight_[static_cast<std::size_t>(h)][iu] = 1.0 / (d + 1e-3 * typical);
      wsum += weight_[static_cast<std::size_t>(h)][iu];
      confidence_[static_cast<std::size_t>(h)][iu] = threshold > 0 ? std::max(0.0, 1.0 - d / threshold) : typical / (typical + d);
    }
    for (int i = 0; i < got; ++i) weight_[static_cast<std::size_t>(h)][static_cast<std::size_t>(i)] /= wsum;
  }
  const int nl = match_count_[0], nr = match_count_[1];
  if (nl == 0 && nr == 0) return false;
  auto mean_conf = [&](int h) {
    double s = 0;
    for (int i = 0; i < match_count_[static_cast<std::size_t>(h)]; ++i) s += confidence_[static_cast<std::size_t>(h)][static_cast<std::size_t>(i)];
    return match_count_[static_cast<std::size_t>(h)] ? s / match_count_[static_cast<std::size_t>(h)] : 0.0;
  };
  const double cl = mean_conf(0), cr = mean_conf(1);
  double weight_total = 0;
  for (int j = 0; j < n; ++j) {
    const auto ju = static_cast<std::size_t>(j);
    // Which match sets drive this joint, and how much each counts.
    double share[2] = {0, 0};
    double joint_weight = 0;
    switch (group_[ju]) {
      case LeftArm:
        share[nl ? 0 : 1] = 1;
        joint_weight = nl ? cl : 0.5 * cr;
        break;
      case RightArm:
        share[nr ? 1 : 0] = 1;
        joint_weight = nr ? cr : 0.5 * cl;
        break;
      case Body:
        if (nl && nr) share[0] = share[1] = 0.5;
        else share[nl ? 0 : 1] = 1;
        joint_weight = (nl && nr) ? 0.5 * (cl + cr) : 0.5 * (nl ? cl : cr);
        break;
    }
    weight_total += joint_weight;
    Eigen::Vector4d acc = Eigen::Vector4d::Zero();
    Eigen::Vector4d ref = Eigen::Vector4d::Zero();
    for (int h = 0; h < 2; ++h) {
      if (share[h] == 0) continue;
      for (int i = 0; i < match_count_[static_cast<std::size_t>(h)]; ++i) {
        const auto iu = static_cast<std::size_t>(i);
        Eigen::Vector4d q;
        if (j == 0) {
          const Quat& r0 = root_aligned_[static_cast<std::size_t>(h)][iu];
          q = {r0.w(), r0.x(), r0.y(), r0.z()};
        } else {
          const float* rot = pose_rot_[static_cast<std::size_t>(h)][iu];
          q = {rot[4 * ju], rot[4 * ju + 1], rot[4 * ju + 2], rot[4 * ju + 3]};
        }
        if (ref.isZero()) ref = q;
        const double wq = share[h] * weight_[static_cast<std::size_t>(h)][iu];
        acc += (q.dot(ref) < 0 ? -wq : wq) * q;  // same hemisphere as the first candidate
      }
    }
    const double len = acc.norm();
    synth_.rotations[ju] = len > 1e-12 ? Quat(acc[0] / len, acc[1] / len, acc[2] / len, acc[3] / len) : Quat::Identity();
  }
  match_weight_ = std::clamp(weight_total / n, 0.0, 1.0);
  return true;
}

void Accentuator::make_direct_pose(const TrackerFrame&) {
  for (std::size_t j = 0; j < direct_.rotations.size(); ++j) direct_.rotations[j] = neutral_.rotations[j];
  direct_.rotations[0] = Quat(Eigen::AngleAxisd(yaw_of(last_head_rot_), Vec3::UnitY())) * neutral_.rotations[0];
}

// Exact critically damped spring per joint toward this frame's rotation
// (closed form, so any dt gives the same curve): unlike the EWMA alone, the
// output's angular velocity stays continuous when the candidate set switches.
void Accentuator::spring_filter(double dt) {
  const std::size_t n = out_.rotations.size();
  if (!have_spring_) {
    for (std::size_t j = 0; j < n; ++j) {
      spring_rot_[j] = out_.rotations[j];
      spring_vel_[j] = Vec3::Zero();
    }
    have_spring_ = true;
    return;
  }
  const double y = 2.0 * std::log(2.0) / cfg_.smooth_halflife;  // half the damping
  const double decay = std::exp(-y * dt);
  for (std::size_t j = 0; j < n; ++j) {
    const Quat& goal = out_.rotations[j];
    const Vec3 j0 = rotation_log(spring_rot_[j] * goal.conjugate());
    const Vec3 j1 = spring_vel_[j] + j0 * y;
    spring_rot_[j] = (rotation_exp(decay * (j0 + j1 * dt)) * goal).normalized();
    spring_vel_[j] = decay * (spring_vel_[j] - j1 * y * dt);
    out_.rotations[j] = spring_rot_[j];
  }
}

void Accentuator::finish_pose(const Quat& head_rotation, const Vec3& head_position, double ik_weight) {
  const int n = skel_.joint_count();
  const auto& r = skel_.roles;
  const int head = r[Role::Head];
  if (cfg_.joint_limits)
    for (int j = 1; j < n; ++j) {
      const auto& l = limit_[static_cast<std::size_t>(j)];
      if (l.swing > 0 || l.twist > 0) out_.rotations[static_cast<std::size_t>(j)] = clamp_rotation(out_.rotations[static_cast<std::size_t>(j)], l.axis, l.swing, l.twist);
    }
  if (cfg_.drive_head) {
    // Head model rotation = the headset's; its local rotation follows from its parents.
    Quat parent = Quat::Identity();
    for (int j = 0; j < head; ++j) {
      const auto ju = static_cast<std::size_t>(j);
      const int p = skel_.parents[ju];
      model_rot_[ju] = p < 0 ? out_.rotations[ju] : model_rot_[static_cast<std::size_t>(p)] * out_.rotations[ju];
    }
    const int hp = skel_.parents[static_cast<std::size_t>(head)];
    if (hp >= 0) parent = model_rot_[static_cast<std::size_t>(hp)];
    out_.rotations[static_cast<std::size_t>(head)] = (parent.conjugate() * head_rotation).normalized();
  }
  for (int j = 0; j < n; ++j) out_.translations[static_cast<std::size_t>(j)] = skel_.rest_offsets[static_cast<std::size_t>(j)];
  out_.translations[0] = Vec3::Zero();
  forward_kinematics(skel_, out_.ref(), model_);
  // Place the body so its head joint sits at the headset.
  const Vec3 shift = head_position - model_[static_cast<std::size_t>(head)].translation;
  out_.translations[0] = shift;
  for (auto& t : model_) t.translation += shift;
#if LEGWORK_ACCENT_HAVE_IK
  if (ik_weight > 1e-6) {
    const Quat yaw(Eigen::AngleAxisd(yaw_of(head_rotation), Vec3::UnitY()));
    for (int h = 0; h < 2; ++h) {
      const auto chain = h == 0 ? ik::left_arm(skel_) : ik::right_arm(skel_);
      ik::TwoBoneTarget target;
      // Exaggerated hands (as matched), so the style control survives hand IK.
      target.position = head_position + cfg_.exaggeration * hand_offset_[static_cast<std::size_t>(h)];
      // Elbows bend down and back, slightly outward.
      target.hint = model_[static_cast<std::size_t>(chain.mid)].translation + yaw * Vec3(h == 0 ? 0.3 : -0.3, -0.5, -0.4) * scale_;
      target.position_weight = std::clamp(ik_weight, 0.0, 1.0);
      target.hint_weight = 1.0;
      ik::solve_two_bone(skel_, chain, target, out_.ref(), model_);
    }
  }
#else
  (void)ik_weight;
#endif
}

FrameInfo Accentuator::update(const TrackerFrame& in) {
  FrameInfo info;
  if (!std::isfinite(in.time) || (started_ && in.time <= last_time_)) {
    info.status = FrameStatus::Rejected;
    info.match_weight = match_weight_;
    info.fallback = fallback_;
    return info;
  }
  const double fps = db_->feature_space().fps;
  const double dt = started_ ? in.time - last_time_ : 1.0 / fps;
  started_ = true;
  last_time_ = in.time;

  // Devices: hold the last good data of anything invalid or non-finite.
  bool lost = false;
  if (in.head.valid && finite(in.head.position) && finite(in.head.rotation)) {
    last_head_ = in.head.position;
    last_head_rot_ = in.head.rotation.normalized();
    have_head_ = true;
  } else {
    lost = true;
  }
  const DeviceSample* hands[2] = {&in.left, &in.right};
  for (int h = 0; h < 2; ++h) {
    if (hands[h]->valid && finite(hands[h]->position) && have_head_)
      hand_offset_[static_cast<std::size_t>(h)] = hands[h]->position - last_head_;
    else
      lost = true;
  }
  ring_head_ = (ring_head_ + 1) % kRing;
  ring_size_ = std::min(ring_size_ + 1, kRing);
  Sample& s = ring_[static_cast<std::size_t>(ring_head_)];
  s.t = in.time;
  s.head = last_head_;
  s.hand = {last_head_ + hand_offset_[0], last_head_ + hand_offset_[1]};

  const double threshold = cfg_.threshold > 0 ? cfg_.threshold * db_->typical_distance() : 0.0;
  const bool matched = have_head_ && !cfg_.direct_only && blend_candidates(threshold);
  if (!matched) match_count_ = {0, 0};
  if (matched) {
    const double w = cfg_.smooth && have_smoothed_ ? std::max(match_weight_, cfg_.min_smoothing_weight) : 1.0;
    for (std::size_t j = 0; j < smoothed_.rotations.size(); ++j)
      smoothed_.rotations[j] = w >= 1.0 ? synth_.rotations[j] : slerp(smoothed_.rotations[j], synth_.rotations[j], w);
    have_smoothed_ = true;
  } else {
    match_weight_ = 0;
  }
  // Converge toward the direct mapping while unmatched or tracking is lost.
  const double target = (!matched || lost) ? 1.0 : 0.0;
  const double step = cfg_.fallback_seconds > 0 ? dt / cfg_.fallback_seconds : 1.0;
  fallback_ += std::clamp(target - fallback_, -step, step);
  if (!have_smoothed_ || cfg_.direct_only) fallback_ = 1.0;
  make_direct_pose(in);
  for (std::size_t j = 0; j < out_.rotations.size(); ++j)
    out_.rotations[j] = fallback_ <= 0 ? smoothed_.rotations[j]
                        : fallback_ >= 1 ? direct_.rotations[j]
                                         : slerp(smoothed_.rotations[j], direct_.rotations[j], fallback_);
  if (cfg_.smooth && cfg_.smooth_halflife > 0 && !cfg_.direct_only) spring_filter(dt);
  finish_pose(last_head_rot_, last_head_, std::max(cfg_.hand_ik, fallback_));
  // Never hand out a broken pose: fall back to the neutral one.
  bool ok = finite(out_.translations[0]);
  for (const auto& q : out_.rotations) ok = ok && finite(q);
  if (!ok) {
    out_ = neutral_;
    out_.translations[0] = last_head_;
  }

  info.match_weight = match_weight_;
  info.fallback = fallback_;
  info.matches = match_count_;
  const double typical = db_->typical_distance();
  for (int h = 0; h < 2; ++h)
    info.best_distance[static_cast<std::size_t>(h)] = match_count_[static_cast<std::size_t>(h)]
        ? static_cast<float>(matches_[static_cast<std::size_t>(h)][0].distance / typical) : 0.0f;
  info.status = lost ? FrameStatus::TrackingLost
                : !matched ? FrameStatus::Unmatched
                : (match_count_[0] == 0 || match_count_[1] == 0) ? FrameStatus::Partial
                                                                  : FrameStatus::Matched;
  return info;
}

std::vector<TrackerFrame> tracker_frames_from_motion(const Motion& m) {
  const auto& r = m.skeleton.roles;
  for (Role need : {Role::Head, Role::LeftHand, Role::RightHand})
    if (!r.has(need)) throw Error("accent: the input skeleton has no " + std::string(role_name(need)) + " joint (needed as a tracked device)");
  std::vector<TrackerFrame> out(static_cast<std::size_t>(m.frame_count()));
  std::vector<Transform> model(static_cast<std::size_t>(m.joint_count()));
  for (int f = 0; f < m.frame_count(); ++f) {
    forward_kinematics(m.skeleton, m.frame(f), model);
    auto& t = out[static_cast<std::size_t>(f)];
    t.time = f / m.fps;
    t.head = {model[static_cast<std::size_t>(r[Role::Head])].translation, model[static_cast<std::size_t>(r[Role::Head])].rotation, true};
    t.left = {model[static_cast<std::size_t>(r[Role::LeftHand])].translation, model[static_cast<std::size_t>(r[Role::LeftHand])].rotation, true};
    t.right = {model[static_cast<std::size_t>(r[Role::RightHand])].translation, model[static_cast<std::size_t>(r[Role::RightHand])].rotation, true};
  }
  return out;
}

AccentRun accentuate(const Database& db, const AccentConfig& cfg, std::span<const TrackerFrame> frames, double fps) {
  Accentuator acc(db, cfg);
  AccentRun run;
  run.output = Motion(acc.skeleton(), fps, static_cast<int>(frames.size()));
  run.info.resize(frames.size());
  double seconds = 0;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    run.info[f] = acc.update(frames[f]);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    run.output.set_frame(static_cast<int>(f), acc.pose());
  }
  run.seconds = seconds;
  return run;
}

AccentRun accentuate_motion(const Database& db, AccentConfig cfg, const Motion& input) {
  const double fps = db.feature_space().fps;
  const Motion m = std::abs(input.fps - fps) > 1e-9 ? resample(input, fps) : input;
  if (cfg.user_height <= 0) cfg.user_height = measure_body(m.skeleton).standing_height;
  const auto frames = tracker_frames_from_motion(m);
  return accentuate(db, cfg, frames, fps);
}

}  // namespace legwork::accent
