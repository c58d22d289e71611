#pragma once
// The key-frame baseline's offline side: a loopable walk cycle cut from a
// mocap walking trial, and the baseline run beside a walking-in-place run
// (its ankle depths, and optionally its poses on the avatar).
// Offline: allocates, throws legwork::Error.
#include <legwork/core/motion.hpp>
#include <legwork/wip/baseline.hpp>
#include <legwork/wip/wip.hpp>

#include <span>
#include <vector>

namespace legwork::wip {

// One gait cycle (left foot-strike to the next) from a walking trial, made
// in place (the root's horizontal progression removed, turned to face +z),
// ready to loop. Throws legwork::Error if no clean cycle is found.
Motion extract_walk_cycle(const Motion& walking_trial);

struct BaselineRun {
  std::vector<double> z[2];  // baseline ankle depths per frame, m
};
// Drives the key-frame baseline (cycle scaled to model's leg) with the
// walking/stopped decisions of `frames` at `rate` Hz. With `avatar_motion`
// (frames of model.skeleton(), one per info frame) the baseline's poses
// replace them, joint by name, moving forward like the method; throws if the
// cycle shares too few joint names with the avatar.
BaselineRun run_keyframe_baseline(const Model& model, const Motion& cycle, std::span<const Info> frames, double rate,
                                  Motion* avatar_motion = nullptr);

}  // namespace legwork::wip
