#pragma once
// The document's comparison condition: the same gait state machines trigger a
// canned walk-cycle clip while the user steps and an idle pose when stopped.
// Offline: extract_walk_cycle builds the clip from a mocap walking trial.
// Runtime: KeyframeBaseline::update is allocation-free.
#include <legwork/core/motion.hpp>

#include <vector>

namespace legwork::wip {

// One gait cycle (left foot-strike to the next) from a walking trial, made
// in place (the root's horizontal progression removed, turned to face +z),
// ready to loop. Throws legwork::Error if no clean cycle is found.
Motion extract_walk_cycle(const Motion& walking_trial);

// Per-frame ankle depth (m, forward +) relative to the pelvis for a motion
// facing +z, e.g. a cycle from extract_walk_cycle.
std::vector<double> ankle_depths(const Motion& m, int foot);

struct KeyframeBaselineModel {
  Motion clip;                 // looping in-place walk cycle
  Pose idle;                   // standing pose
  std::vector<double> depth[2];  // clip ankle depth per frame, scaled to the avatar
  double blend_tau = 0.15;     // s: cross-fade between idle and walking
};
// `avatar_leg` scales the clip's depths (clip leg -> avatar leg).
KeyframeBaselineModel make_keyframe_baseline(const Motion& cycle, double avatar_leg);

struct KeyframeBaselineState {
  double clip_time = 0, weight = 0;
  Pose pose;           // output pose (clip skeleton)
  double z[2] = {0, 0};  // output ankle depths, m
};
KeyframeBaselineState make_baseline_state(const KeyframeBaselineModel& m);
// `walking`: the state machines say the user is stepping (not stopped).
void update_baseline(const KeyframeBaselineModel& m, bool walking, double dt, KeyframeBaselineState& s);

}  // namespace legwork::wip
