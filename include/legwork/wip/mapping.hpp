#pragma once
// The document's kinematic mapping from tracked foot height to IK-target
// depth (equations 1-4) and to body/target heights (equations 5-8). Pure
// functions; all lengths in metres, depth z forward-positive in the avatar's
// local frame (relative to the pelvis).
namespace legwork::wip {

struct StepShape {
  double S = 0.6;  // maximum step length of the avatar
  double H = 0.3;  // maximum step height of the user; lambda = 4H
  double lambda() const { return 4 * H; }
};

// First step (eq. 1, 2): the swinging foot s moves 0 -> S/4 (ascending) ->
// S/2 (descending); the other foot o moves 0 -> -S/4 -> -S/2. h is clamped to [0, H].
double first_step_swing(const StepShape& k, double h, bool ascending);
double first_step_support(const StepShape& k, double h, bool ascending);
// Consecutive steps (eq. 3, 4): swing -S/2 -> 0 -> +S/2 (with the strike
// overshoot term 0.25 S sin(4 pi h / lambda) while descending); support
// +S/2 -> 0 -> -S/2. Both are driven by the swinging foot's height.
double next_step_swing(const StepShape& k, double h, bool ascending);
double next_step_support(const StepShape& k, double h, bool ascending);
// Eq. 5: body drop for the trailing foot's depth, leg length L.
double body_drop(double leg_length, double z_trail);

}  // namespace legwork::wip
