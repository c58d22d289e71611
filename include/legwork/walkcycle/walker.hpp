#pragma once
// Runtime walking, frame by frame: the same no-slip pivoting as walk_path,
// but steered live (e.g. by a game's stick) instead of along a known path.
//
// Const model (CycleModel) + mutable state (WalkerState): walker_update()
// allocates nothing, throws nothing and touches only the state and the output
// pose, so many characters can share one model across threads.
// The heading asked for is taken once per step, at the middle of the previous
// step, limited to `max_turn_per_step`, and blended in over the next step
// (document 001: no heading keys in the first half of step n and the second
// half of step n-1); every turn is applied about the planted pivot.
#include <legwork/walkcycle/cycle.hpp>

#include <array>

namespace legwork::walkcycle {

struct WalkerState {
  double time = 0;            // cycle frames since the start (contact of the left foot)
  double heading_from = 0;    // radians about y, 0 = facing +z
  double heading_to = 0;
  int decided_step = 0;       // last step whose heading has been latched
  double heading = 0;         // current heading, radians
  Vec3 offset = Vec3::Zero();  // world = yaw(heading) * in-place + offset (floor, y = 0)
  std::array<Vec3, 4> feet{};  // in-place heel/ball of right/left foot at `time`
  double max_turn_per_step = deg2rad(30.0);
};

// Starts a walk at a contact with the root above `position` (floor point,
// y ignored), facing `heading`. Writes the first pose to `out` if non-empty.
void walker_reset(const CycleModel& m, WalkerState& s, const Vec3& position, double heading, PoseRef out);

// Advances by `seconds` (at the walk's rate, m.fps cycle frames per second),
// steering towards `desired_heading` (radians), and writes the world pose.
void walker_update(const CycleModel& m, WalkerState& s, double seconds, double desired_heading, PoseRef out);

}  // namespace legwork::walkcycle
