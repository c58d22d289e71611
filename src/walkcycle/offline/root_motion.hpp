#pragma once
// Smooth root motion for walk_path (private to walkcycle_offline): the root
// travels at a smoothed speed while two-bone leg IK keeps the feet where the
// pivoting walk planted them (issue 14, item 1). See root_motion.cpp.
#include <legwork/walkcycle/offline/walk.hpp>

#include <span>
#include <vector>

namespace legwork::walkcycle {

// Average of the piecewise-linear series `q` (one value per frame) over a
// window of `width` frames centred on each frame, the series extended beyond
// its ends by straight lines at its mean velocity over the first / last
// `width` frames (at the end: held still if `rest_at_end`). A window of
// exactly one step removes everything that repeats every step (the lunge and
// stall of a pivoting root).
std::vector<Vec3> window_average(std::span<const Vec3> q, double width, bool rest_at_end);

// Replaces the pivoting root of `r.motion` by a smooth one and solves both
// legs by two-bone IK so each ankle stays where the pivoting walk put it (in
// position and rotation: the stance foot stays planted, the swing foot keeps
// its world path). `floor_offset` is the pivoting walk's per-frame floor
// offset (world root = yaw(heading) * in-place root + offset); it is
// smoothed over one step twice (`step_frames` output frames per step), so
// the root keeps the pelvis's own offsets from the keys but not the drag of
// the planted foot. An ankle out of reach rolls its foot about the ball
// (trailing) or heel (leading) first; what is still out of reach is pulled in
// by the soft limit. Uneven `ground`: each foot's heel and ball rise by the
// ground under them (fit_to_ground), the pelvis by the ground under the feet
// averaged over a step; on stairs each foot is planted flat on a tread and
// carried between treads in the swing. With opt.turn_on_ball a stance foot
// keeps the yaw it landed with while its heel is down and turns on its ball
// as the heel rises (its pivot held). Fills r.leg_reach_max,
// r.foot_roll_max, r.pelvis_drop_max, r.reach_limited_frames,
// r.ground_lift_max.
void smooth_root_motion(const CycleModel& m, const Ground& ground, std::span<const Vec3> floor_offset, double step_frames,
                        const WalkOptions& opt, WalkResult& r);

}  // namespace legwork::walkcycle
