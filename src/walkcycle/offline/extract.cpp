#include <legwork/core/contacts.hpp>
#include <legwork/core/series.hpp>
#include <legwork/core/stats.hpp>
#include <legwork/core/rotation.hpp>
#include <legwork/walkcycle/offline/extract.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/mirror.hpp>
#include <legwork/walkcycle/cycle.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <deque>
#include <numeric>

namespace legwork::walkcycle {

namespace {


// Pose with the heading `psi` taken out of the root and the root put at
// (0, y, 0); mirrored (left <-> right) if `mirror`.
Pose normalised_pose(const Motion& clip, int f, double psi, bool mirror) {
  Pose p(clip.skeleton);
  const auto src = clip.frame(f);
  std::copy(src.rotations.begin(), src.rotations.end(), p.rotations.begin());
  std::copy(src.translations.begin(), src.translations.end(), p.translations.begin());
  p.rotations[0] = yaw_rotation(-psi) * p.rotations[0];
  p.translations[0] = Vec3(0, p.translations[0].y(), 0);
  if (!mirror) return p;
  Pose q(clip.skeleton);
  mirror_pose(clip.skeleton, p, q.ref());
  return q;
}

// Normalised mean of rotations (sign-aligned to the first).
Quat mean_rotation(const std::vector<Quat>& qs) {
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  for (const auto& q : qs) sum += (q.coeffs().dot(qs.front().coeffs()) < 0 ? -1.0 : 1.0) * q.coeffs();
  return Quat(sum / sum.norm());
}

KeyPose key_from_pose(const Pose& p) {
  KeyPose k;
  for (int j = 0; j < static_cast<int>(p.rotations.size()); ++j) k.set(j, p.rotations[static_cast<std::size_t>(j)]);
  k.root_offset = Vec3::Zero();
  k.height_on_floor = true;
  return k;
}

}  // namespace

namespace {

// Joint positions of every frame of a clip (model space), by frame and joint.
struct ClipPositions {
  std::vector<Vec3> pos;
  int J = 0;
  const Vec3& operator()(int f, int j) const { return pos[static_cast<std::size_t>(f * J + j)]; }
};

// Every complete step: strikes of both feet merged in time order, pass, down and up.
void find_steps(const Motion& clip, const ClipPositions& P, const ExtractOptions& opt, Extraction& ex) {
  const Skeleton& s = clip.skeleton;
  const int la = s.roles[Role::LeftAnkle], ra = s.roles[Role::RightAnkle];
  std::vector<std::pair<int, bool>> strikes;
  for (int f : foot_strikes(clip, 0, opt.contacts)) strikes.emplace_back(f, true);
  for (int f : foot_strikes(clip, 1, opt.contacts)) strikes.emplace_back(f, false);
  std::sort(strikes.begin(), strikes.end());

  for (std::size_t i = 0; i + 1 < strikes.size(); ++i) {
    const auto [c, left] = strikes[i];
    const auto [nc, next_left] = strikes[i + 1];
    if (left == next_left || nc - c < 4) continue;  // a missed strike in between
    StepEvents e;
    e.left = left;
    e.contact = c;
    e.next_contact = nc;
    Vec3 dir = P(nc, 0) - P(c, 0);
    dir.y() = 0;
    if (dir.norm() < 1e-3) continue;  // not travelling
    dir.normalize();
    const int stance = left ? la : ra, swing = left ? ra : la;
    e.pass = -1;
    for (int f = c; f <= nc; ++f)
      if ((P(f, swing) - P(f, stance)).dot(dir) >= 0) {
        e.pass = f;
        break;
      }
    if (e.pass <= c + 1 || e.pass >= nc - 1) continue;
    e.down = c + 1;
    for (int f = c + 1; f < e.pass; ++f)
      if (P(f, 0).y() < P(e.down, 0).y()) e.down = f;
    e.up = e.pass + 1;
    for (int f = e.pass + 1; f < nc; ++f)
      if (P(f, 0).y() > P(e.up, 0).y()) e.up = f;
    ex.steps.push_back(e);
  }
}

// Steady steps: typical duration and little turning.
void mark_steady(const Motion& clip, Extraction& ex) {
  std::vector<double> durations;
  for (const auto& e : ex.steps) durations.push_back(e.next_contact - e.contact);
  const double median = percentile(durations, 0.5);
  for (auto& e : ex.steps) {
    const double d = e.next_contact - e.contact;
    const double turn = wrap_angle(yaw_of(clip.frame(e.next_contact).rotations[0]) - yaw_of(clip.frame(e.contact).rotations[0]));
    e.used = std::abs(d - median) <= 0.25 * median && std::abs(turn) < deg2rad(25);
    ex.steps_used += e.used;
  }
  if (ex.steps_used < 2)
    throw Error("extract: found " + std::to_string(ex.steps_used) + " steady steps (of " + std::to_string(ex.steps.size()) +
                "); a walking clip with at least two steady steps is needed");

}

// Average each key over the steady steps, right-foot steps mirrored.
void average_keys(const Motion& clip, const ClipPositions& P, const ExtractOptions& opt, Extraction& ex) {
  const int J = P.J;
  const std::array<int StepEvents::*, kKeyCount> key_of{&StepEvents::contact, &StepEvents::down, &StepEvents::pass, &StepEvents::up};
  std::array<std::vector<std::vector<Quat>>, kKeyCount> rots;
  for (auto& r : rots) r.assign(static_cast<std::size_t>(J), {});
  std::array<double, kKeyCount> frac{};
  double step_seconds = 0;
  for (const auto& e : ex.steps) {
    if (!e.used) continue;
    Vec3 dir = P(e.next_contact, 0) - P(e.contact, 0);
    const double psi = std::atan2(dir.x(), dir.z());
    const double len = e.next_contact - e.contact;
    step_seconds += len / clip.fps;
    for (int k = 0; k < kKeyCount; ++k) {
      const Pose p = normalised_pose(clip, e.*key_of[static_cast<std::size_t>(k)], psi, !e.left);
      for (int j = 0; j < J; ++j) rots[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)].push_back(p.rotations[static_cast<std::size_t>(j)]);
      frac[static_cast<std::size_t>(k)] += (e.*key_of[static_cast<std::size_t>(k)] - e.contact) / len;
    }
  }
  step_seconds /= ex.steps_used;
  ex.cycle_seconds = 2 * step_seconds;
  WalkKeys& keys = ex.keys;
  keys.fps = opt.fps;
  keys.frames_per_cycle = opt.frames_per_cycle > 0 ? opt.frames_per_cycle
                                                    : std::max(8, 2 * static_cast<int>(std::lround(step_seconds * opt.fps)));
  const double half = keys.frames_per_cycle / 2.0;
  keys.description = "Extracted from a motion-capture walk: key poses averaged over " + std::to_string(ex.steps_used) +
                     " steady steps (right-foot steps mirrored).";
  for (int k = 0; k < kKeyCount; ++k) {
    keys.key_frames[static_cast<std::size_t>(k)] = std::round(frac[static_cast<std::size_t>(k)] / ex.steps_used * half * 100) / 100;
    KeyPose kp;
    for (int j = 0; j < J; ++j) kp.set(j, mean_rotation(rots[static_cast<std::size_t>(k)][static_cast<std::size_t>(j)]));
    kp.root_offset = Vec3::Zero();
    kp.height_on_floor = true;
    keys.keys[static_cast<std::size_t>(k)] = kp;
  }
  for (int k = 1; k < kKeyCount; ++k)  // keep the keys strictly ordered after rounding
    keys.key_frames[static_cast<std::size_t>(k)] =
        std::max(keys.key_frames[static_cast<std::size_t>(k)], keys.key_frames[static_cast<std::size_t>(k - 1)] + 0.25);
  keys.key_frames[3] = std::min(keys.key_frames[3], half - 0.25);

}

// A walk always has a foot on the floor (double support, no flight); a run
// or a hop has frames with both feet in the air. A foot is down as
// foot_contacts (core/contacts.hpp) says. Measured over the steady steps; on
// the shared CMU clips walks measure 0-6 %, 32 of 34 runs over 10 % (up to 44 %).
void measure_flight(const Motion& clip, const ExtractOptions& opt, Extraction& ex) {
  const auto down = foot_contacts(clip, opt.contacts);
  int frames = 0, flight = 0;
  for (const auto& e : ex.steps) {
    if (!e.used) continue;
    for (int f = e.contact; f < e.next_contact; ++f, ++frames)
      flight += !down[0][static_cast<std::size_t>(f)] && !down[1][static_cast<std::size_t>(f)];
  }
  ex.flight_fraction = frames ? static_cast<double>(flight) / frames : 0.0;
}

// Re-synthesis: the cycle from the keys against the clip's mean step,
// pelvis-relative joint positions, heading removed, S phases per step.
void resynthesis(const Motion& clip, const ClipPositions& P, Extraction& ex) {
  const Skeleton& s = clip.skeleton;
  const int J = P.J;
  const double half = ex.keys.frames_per_cycle / 2.0;
  const CycleModel model = build_cycle(s, ex.keys);
  constexpr int S = 16;
  std::vector<Vec3> real(static_cast<std::size_t>(S * J), Vec3::Zero());
  for (const auto& e : ex.steps) {
    if (!e.used) continue;
    Vec3 dir = P(e.next_contact, 0) - P(e.contact, 0);
    const double psi = std::atan2(dir.x(), dir.z());
    for (int i = 0; i < S; ++i) {
      const int f = e.contact + static_cast<int>(std::lround(static_cast<double>(i) / S * (e.next_contact - e.contact)));
      Pose p = normalised_pose(clip, f, psi, !e.left);
      p.translations[0] = Vec3::Zero();
      const auto q = joint_positions(s, p);
      for (int j = 0; j < J; ++j) real[static_cast<std::size_t>(i * J + j)] += q[static_cast<std::size_t>(j)] / ex.steps_used;
    }
  }
  Pose syn(s);
  double sum = 0;
  for (int i = 0; i < S; ++i) {
    sample_cycle(model, half * i / S, syn.ref());
    syn.translations[0] = Vec3::Zero();
    const auto q = joint_positions(s, syn);
    for (int j = 0; j < J; ++j) {
      const double d = (q[static_cast<std::size_t>(j)] - real[static_cast<std::size_t>(i * J + j)]).norm() * 1000;
      sum += d;
      ex.resynthesis_max_mm = std::max(ex.resynthesis_max_mm, d);
    }
  }
  ex.resynthesis_mean_mm = sum / (S * J);
}

}  // namespace

Extraction extract_walk(const Motion& clip, const ExtractOptions& opt) {
  const Skeleton& s = clip.skeleton;
  for (Role r : {Role::Pelvis, Role::LeftAnkle, Role::RightAnkle})
    if (!s.roles.has(r)) throw Error("extract: the clip's skeleton has no joint for role '" + std::string(role_name(r)) + "'");
  if (clip.frame_count() < 10) throw Error("extract: the clip is too short");
  const ClipPositions P{joint_positions(clip), clip.joint_count()};
  Extraction ex;
  find_steps(clip, P, opt, ex);
  mark_steady(clip, ex);
  measure_flight(clip, opt, ex);
  if (ex.flight_fraction > opt.max_flight_fraction) {
    char pct[64];
    std::snprintf(pct, sizeof pct, "%.0f %%", ex.flight_fraction * 100);
    ex.warning = std::string("this does not look like a walk: both feet are off the floor in ") + pct +
                 " of the steady steps' frames (a walk always has a foot down; a run or a hop does not)";
    if (opt.refuse_non_walks) throw Error("extract: " + ex.warning + "; give a walking clip");
  }
  average_keys(clip, P, opt, ex);
  resynthesis(clip, P, ex);
  return ex;
}

WalkKeys keys_from_frames(const Motion& clip, const std::vector<int>& frames, int frames_per_cycle, double fps) {
  if (frames.size() != kKeyCount) throw Error("--keys: give four frames: contact, down, pass, up");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (frames[i] < 0 || frames[i] >= clip.frame_count())
      throw Error("--keys: frame " + std::to_string(frames[i]) + " is outside the clip's frames 0:" + std::to_string(clip.frame_count() - 1));
    if (i > 0 && frames[i] <= frames[i - 1]) throw Error("--keys: the four frames must increase (contact < down < pass < up)");
  }
  if (frames_per_cycle < 8 || frames_per_cycle % 2) throw Error("--frames: expected an even number, at least 8");
  const Skeleton& s = clip.skeleton;
  // Heading: the pelvis's mean facing over the four frames.
  double sx = 0, sz = 0;
  for (int f : frames) {
    const Vec3 fw = clip.frame(f).rotations[0] * Vec3::UnitZ();
    sx += fw.x(), sz += fw.z();
  }
  const double psi = std::atan2(sx, sz);
  // Left foot in front at contact, else mirror everything.
  const auto p0 = joint_positions(s, clip.frame(frames[0]));
  const Vec3 fwd(std::sin(psi), 0, std::cos(psi));
  const bool mirror = (p0[static_cast<std::size_t>(s.roles[Role::LeftAnkle])] - p0[static_cast<std::size_t>(s.roles[Role::RightAnkle])]).dot(fwd) < 0;
  WalkKeys keys;
  keys.frames_per_cycle = frames_per_cycle;
  keys.fps = fps;
  const double span = (frames[3] - frames[0]) * 4.0 / 3.0;  // contact .. next contact
  const double half = frames_per_cycle / 2.0;
  for (int k = 0; k < kKeyCount; ++k) {
    keys.key_frames[static_cast<std::size_t>(k)] = (frames[static_cast<std::size_t>(k)] - frames[0]) / span * half;
    keys.keys[static_cast<std::size_t>(k)] = key_from_pose(normalised_pose(clip, frames[static_cast<std::size_t>(k)], psi, mirror));
  }
  keys.description = "Key poses taken from frames of a BVH clip.";
  return keys;
}

}  // namespace legwork::walkcycle
