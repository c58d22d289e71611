#pragma once
// The document's comparison condition: the same gait state machines trigger a
// canned walk-cycle clip while the user steps and an idle pose when stopped.
// The clip comes from wip/offline/walk_cycle.hpp (extract_walk_cycle);
// make_keyframe_baseline allocates, update_baseline is allocation-free.
#include <legwork/core/motion.hpp>
#include <legwork/core/tracker.hpp>

#include <vector>

namespace legwork::wip {

// Per-frame ankle depth (m, forward +) relative to the pelvis for a motion
// facing +z, e.g. a cycle from extract_walk_cycle. foot: kLeft or kRight.
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
