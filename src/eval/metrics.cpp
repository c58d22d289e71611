#include <legwork/eval/metrics.hpp>
#include <legwork/core/stats.hpp>

#include <legwork/core/fk.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace legwork::eval {
namespace {

bool is_lower(Role r) {
  switch (r) {
    case Role::Pelvis:
    case Role::LeftHip:
    case Role::LeftKnee:
    case Role::LeftAnkle:
    case Role::LeftToe:
    case Role::RightHip:
    case Role::RightKnee:
    case Role::RightAnkle:
    case Role::RightToe:
      return true;
    default:
      return false;
  }
}

// Roles both tracks have.
std::array<bool, kRoleCount> shared_roles(const RoleTrack& a, const RoleTrack& b) {
  std::array<bool, kRoleCount> s{};
  for (std::size_t r = 0; r < s.size(); ++r) s[r] = a.present[r] && b.present[r];
  return s;
}

// Central-difference velocity of role r at frame f (one-sided at the ends), m/s.
Vec3 velocity(const RoleTrack& t, int f, Role r) {
  const int a = std::max(0, f - 1), b = std::min(t.frames - 1, f + 1);
  if (b == a) return Vec3::Zero();
  return (t.at(b, r) - t.at(a, r)) * (t.fps / (b - a));
}

double mean_of_finite(std::span<const double> v) {
  double s = 0;
  int n = 0;
  for (double x : v)
    if (std::isfinite(x)) {
      s += x;
      ++n;
    }
  return n ? s / n : kNaN;
}

}  // namespace

std::string_view part_name(Part p) {
  switch (p) {
    case Part::LeftHand: return "left_hand";
    case Part::RightHand: return "right_hand";
    case Part::UpperBody: return "upper_body";
    case Part::LowerBody: return "lower_body";
    case Part::FullBody: return "full_body";
    default: return "?";
  }
}

bool role_in_part(Role r, Part p) {
  switch (p) {
    case Part::LeftHand: return r == Role::LeftHand;
    case Part::RightHand: return r == Role::RightHand;
    case Part::UpperBody: return !is_lower(r);  // head, neck, spine, chest, clavicles, arms
    case Part::LowerBody: return is_lower(r);
    case Part::FullBody: return r != Role::Count;
    default: return false;
  }
}

RoleTrack make_track(double fps, int frames, const std::array<bool, kRoleCount>& present) {
  RoleTrack t;
  t.fps = fps;
  t.frames = frames;
  t.present = present;
  t.positions.assign(static_cast<std::size_t>(frames) * kRoleCount, Vec3::Zero());
  return t;
}

RoleTrack role_track(const Motion& m) {
  std::array<bool, kRoleCount> present{};
  for (int r = 0; r < kRoleCount; ++r) present[static_cast<std::size_t>(r)] = m.skeleton.roles.has(static_cast<Role>(r));
  RoleTrack t = make_track(m.fps, m.frame_count(), present);
  std::vector<Vec3> joints(static_cast<std::size_t>(m.joint_count()));
  for (int f = 0; f < m.frame_count(); ++f) {
    forward_positions(m.skeleton, m.frame(f), joints);
    for (int r = 0; r < kRoleCount; ++r)
      if (present[static_cast<std::size_t>(r)])
        t.at(f, static_cast<Role>(r)) = joints[static_cast<std::size_t>(m.skeleton.roles[static_cast<Role>(r)])];
  }
  return t;
}

double mean_jerk(const RoleTrack& t) {
  if (t.frames < 4) return 0;
  const double k = t.fps * t.fps * t.fps;
  double sum = 0;
  long count = 0;
  for (int r = 0; r < kRoleCount; ++r) {
    const auto role = static_cast<Role>(r);
    if (!t.has(role)) continue;
    for (int f = 0; f + 3 < t.frames; ++f) {
      // Third forward difference: x3 - 3 x2 + 3 x1 - x0.
      const Vec3 j = t.at(f + 3, role) - 3.0 * t.at(f + 2, role) + 3.0 * t.at(f + 1, role) - t.at(f, role);
      sum += j.norm() * k;
      ++count;
    }
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

FootSkate foot_skating(const RoleTrack& t, double contact_height) {
  FootSkate out;
  double slide = 0;
  long contact_pairs = 0, joint_frames = 0, contact_frames = 0;
  std::vector<double> heights(static_cast<std::size_t>(t.frames));
  for (Role r : {Role::LeftAnkle, Role::RightAnkle, Role::LeftToe, Role::RightToe}) {
    if (!t.has(r) || t.frames < 2) continue;
    for (int f = 0; f < t.frames; ++f) heights[static_cast<std::size_t>(f)] = t.at(f, r).y();
    // The joint's own floor level: robust to a drifting capture floor and to
    // skeletons whose ankle sits at different heights.
    const double floor = percentile(heights, 0.05);
    auto in_contact = [&](int f) { return heights[static_cast<std::size_t>(f)] < floor + contact_height; };
    for (int f = 0; f < t.frames; ++f) {
      ++joint_frames;
      if (in_contact(f)) ++contact_frames;
      if (f + 1 < t.frames && in_contact(f) && in_contact(f + 1)) {
        Vec3 d = t.at(f + 1, r) - t.at(f, r);
        d.y() = 0;
        slide += d.norm();
        ++contact_pairs;
      }
    }
  }
  out.slide_m = contact_pairs ? slide / static_cast<double>(contact_pairs) : 0.0;
  out.contact_fraction = joint_frames ? static_cast<double>(contact_frames) / static_cast<double>(joint_frames) : 0.0;
  return out;
}

TrialMetrics evaluate_trial(const RoleTrack& output, const RoleTrack& truth, const MetricOptions& opt) {
  if (output.frames != truth.frames)
    throw Error("evaluate_trial: output has " + std::to_string(output.frames) + " frames, ground truth " +
                std::to_string(truth.frames));
  if (std::abs(output.fps - truth.fps) > 1e-9)
    throw Error("evaluate_trial: output rate " + std::to_string(output.fps) + " Hz differs from ground truth " +
                std::to_string(truth.fps) + " Hz");
  const auto shared = shared_roles(output, truth);
  if (std::none_of(shared.begin(), shared.end(), [](bool b) { return b; }))
    throw Error("evaluate_trial: output and ground truth share no role joint");

  TrialMetrics m;
  m.frames = truth.frames;
  const int n = truth.frames;
  std::array<double, kPartCount> sum{};
  std::array<long, kPartCount> count{};
  double vsum = 0;
  long vcount = 0;
  for (int r = 0; r < kRoleCount; ++r) {
    if (!shared[static_cast<std::size_t>(r)]) continue;
    const auto role = static_cast<Role>(r);
    double joint_err = 0, joint_verr = 0;
    for (int f = 0; f < n; ++f) {
      joint_err += (output.at(f, role) - truth.at(f, role)).norm();
      joint_verr += (velocity(output, f, role) - velocity(truth, f, role)).norm();
    }
    for (int p = 0; p < kPartCount; ++p)
      if (role_in_part(role, static_cast<Part>(p))) {
        sum[static_cast<std::size_t>(p)] += joint_err;
        count[static_cast<std::size_t>(p)] += n;
      }
    vsum += joint_verr;
    vcount += n;
  }
  for (int p = 0; p < kPartCount; ++p) {
    const auto pu = static_cast<std::size_t>(p);
    m.part_cm[pu] = count[pu] ? 100.0 * sum[pu] / static_cast<double>(count[pu]) : kNaN;
  }
  m.mpjpe_cm = m.part_cm[static_cast<std::size_t>(Part::FullBody)];
  m.mpjve_cm_s = vcount ? 100.0 * vsum / static_cast<double>(vcount) : kNaN;
  m.jitter = mean_jerk(output) / 100.0;
  m.jitter_truth = mean_jerk(truth) / 100.0;

  // Hand following: input (ground-truth) and output hands, both relative to
  // the input head, as independent x, y, z series.
  const bool head = truth.has(Role::Head);
  std::vector<double> in(static_cast<std::size_t>(n)), out(static_cast<std::size_t>(n));
  int side = 0;
  for (Role hand : {Role::LeftHand, Role::RightHand}) {
    auto& axes = m.hand_correlation_axis[static_cast<std::size_t>(side)];
    for (int a = 0; a < 3; ++a) {
      if (!shared[static_cast<std::size_t>(hand)]) {
        axes[static_cast<std::size_t>(a)] = kNaN;
        continue;
      }
      for (int f = 0; f < n; ++f) {
        const double h = head ? truth.at(f, Role::Head)[a] : 0.0;
        in[static_cast<std::size_t>(f)] = truth.at(f, hand)[a] - h;
        out[static_cast<std::size_t>(f)] = output.at(f, hand)[a] - h;
      }
      axes[static_cast<std::size_t>(a)] = pearson(in, out);
    }
    m.hand_correlation[static_cast<std::size_t>(side)] = mean_of_finite(axes);
    ++side;
  }

  const FootSkate o = foot_skating(output, opt.contact_height), t = foot_skating(truth, opt.contact_height);
  m.foot_skating_cm = 100.0 * o.slide_m;
  m.foot_skating_truth_cm = 100.0 * t.slide_m;
  m.foot_contact_fraction = o.contact_fraction;
  return m;
}

TrialMetrics combine(std::span<const TrialMetrics> trials) {
  TrialMetrics c;
  if (trials.empty()) return c;
  if (trials.size() == 1) return trials[0];
  double w = 0;
  for (const auto& t : trials) w += t.frames;
  // Frame-weighted mean of a field over the trials where it is finite.
  auto wmean = [&](auto get) {
    double s = 0, ws = 0;
    for (const auto& t : trials) {
      const double v = get(t);
      if (std::isfinite(v)) {
        s += v * t.frames;
        ws += t.frames;
      }
    }
    return ws > 0 ? s / ws : kNaN;
  };
  c.frames = static_cast<int>(w);
  for (std::size_t p = 0; p < c.part_cm.size(); ++p) c.part_cm[p] = wmean([p](const TrialMetrics& t) { return t.part_cm[p]; });
  c.mpjpe_cm = c.part_cm[static_cast<std::size_t>(Part::FullBody)];
  c.mpjve_cm_s = wmean([](const TrialMetrics& t) { return t.mpjve_cm_s; });
  c.jitter = wmean([](const TrialMetrics& t) { return t.jitter; });
  c.jitter_truth = wmean([](const TrialMetrics& t) { return t.jitter_truth; });
  for (std::size_t s = 0; s < 2; ++s) {
    for (std::size_t a = 0; a < 3; ++a)
      c.hand_correlation_axis[s][a] = wmean([s, a](const TrialMetrics& t) { return t.hand_correlation_axis[s][a]; });
    c.hand_correlation[s] = wmean([s](const TrialMetrics& t) { return t.hand_correlation[s]; });
  }
  c.foot_skating_cm = wmean([](const TrialMetrics& t) { return t.foot_skating_cm; });
  c.foot_skating_truth_cm = wmean([](const TrialMetrics& t) { return t.foot_skating_truth_cm; });
  c.foot_contact_fraction = wmean([](const TrialMetrics& t) { return t.foot_contact_fraction; });
  return c;
}

}  // namespace legwork::eval
