#include <legwork/wip/offline/walk_cycle.hpp>

#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/rotation.hpp>
#include <legwork/core/contacts.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace legwork::wip {

Motion extract_walk_cycle(const Motion& trial) {
  const auto swings = foot_swings(trial);
  // Consecutive left foot-strikes: candidate cycles; take the one nearest the
  // middle of the trial with a plausible duration.
  std::vector<double> strikes;
  for (const auto& s : swings)
    if (s.foot == kLeft) strikes.push_back(s.strike);
  const double mid = 0.5 * trial.duration();
  int best = -1;
  double best_dist = 1e300;
  for (std::size_t i = 0; i + 1 < strikes.size(); ++i) {
    const double len = strikes[i + 1] - strikes[i];
    const double dist = std::abs(0.5 * (strikes[i] + strikes[i + 1]) - mid);
    if (len > 0.7 && len < 1.8 && dist < best_dist) best_dist = dist, best = static_cast<int>(i);
  }
  if (best < 0) throw Error("no clean walk cycle (two left foot-strikes 0.7-1.8 s apart) found in the trial");
  const int a = static_cast<int>(std::lround(strikes[static_cast<std::size_t>(best)] * trial.fps));
  const int b = static_cast<int>(std::lround(strikes[static_cast<std::size_t>(best) + 1] * trial.fps));
  // Frames [a, b): the frame at b is the loop's start again.
  Motion cycle = trim(trial, a, std::max(a + 1, b - 1));
  const Vec3 p0 = trial.frame(a).translations[0], p1 = trial.frame(b).translations[0];
  Vec3 travel = p1 - p0;
  travel.y() = 0;
  const double yaw = travel.norm() > 1e-6 ? std::atan2(travel.x(), travel.z()) : 0.0;
  const Quat unturn = yaw_rotation(-yaw);
  const int n = cycle.frame_count();
  for (int f = 0; f < n; ++f) {
    auto fr = cycle.frame(f);
    // Remove the straight-line progression, keep the sway; face +z.
    Vec3 rel = fr.translations[0] - p0 - travel * (double(f) / (b - a));
    rel = unturn * rel;
    fr.translations[0] = Vec3(rel.x(), fr.translations[0].y(), rel.z());
    fr.rotations[0] = unturn * fr.rotations[0];
  }
  return cycle;
}

namespace {

// Copies the baseline clip's local rotations onto the avatar, joint by name.
void baseline_to_avatar(const Skeleton& clip, const Pose& from, const Skeleton& avatar, double root_scale, PoseRef to) {
  for (int j = 0; j < avatar.joint_count(); ++j) {
    const int c = clip.find(avatar.names[static_cast<std::size_t>(j)]);
    if (c < 0) continue;
    to.rotations[static_cast<std::size_t>(j)] = from.rotations[static_cast<std::size_t>(c)];
  }
  to.translations[0] = from.translations[0] * root_scale;
}

}  // namespace

BaselineRun run_keyframe_baseline(const Model& model, const Motion& cycle, std::span<const Info> frames, double rate,
                                  Motion* avatar_motion) {
  const auto bm = make_keyframe_baseline(cycle, model.leg_length());
  auto bs = make_baseline_state(bm);
  const double clip_hip = measure_body(cycle.skeleton).hip_height;
  const double root_scale = clip_hip > 0 ? measure_body(model.skeleton()).hip_height / clip_hip : 1.0;
  if (avatar_motion) {
    int missing = 0;
    for (const auto& n : model.skeleton().names) missing += cycle.skeleton.find(n) < 0 ? 1 : 0;
    if (missing > model.skeleton().joint_count() / 2)
      throw Error("the walk-cycle clip shares too few joint names with the avatar (" + std::to_string(missing) + " of " +
                  std::to_string(model.skeleton().joint_count()) + " avatar joints missing)");
  }
  BaselineRun out;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    update_baseline(bm, frames[i].walking, 1.0 / rate, bs);
    for (int f = 0; f < 2; ++f) out.z[f].push_back(bs.z[f]);
    if (!avatar_motion || static_cast<int>(i) >= avatar_motion->frame_count()) continue;
    auto fr = avatar_motion->frame(static_cast<int>(i));
    baseline_to_avatar(cycle.skeleton, bs.pose, model.skeleton(), root_scale, fr);
    // The baseline moves with the same forward speed as the method.
    fr.translations[0].x() += frames[i].root_position.x();
    fr.translations[0].z() += frames[i].root_position.z();
  }
  return out;
}

}  // namespace legwork::wip
