#pragma once
// Walking forward without foot slip, straight or along a curved path
// (document 001, section 3.5).
//
// Per frame, the root is moved so the stance foot's pivot stays where it
// was on the previous frame: the heel from contact until the pass key, the
// ball from the pass key to the next contact (the document's heel-then-ball
// rule, extended to any skeleton: heel = ankle projected to the floor,
// ball = toe base projected to the floor, both fixed in the foot's frame).
// The paper tracks only the pivot's z; here both horizontal axes are kept,
// which also carries the pelvis's side sway into the root.
//
// Curved paths: the character turns only about y (the paper's root rotate Y,
// heading theta_n per path segment); heading changes are spread from the
// middle of one step to the middle of the next, and every rotation is applied
// about the planted pivot, so the stance foot stays put while the body turns
// (with the smooth root the legs then turn the stance foot on its ball
// instead of with the body: WalkOptions::turn_on_ball).
// Each step's heading is decided at the middle of the previous step: the
// path's direction one step further on (where the heading will have blended
// in), corrected towards the path by atan(offset / two steps).
// At the path's end the last step blends into the standing pose.
//
// walk_path() is offline code: it sizes the output motion from the expected
// walk (growing it if the walk runs longer) and may throw legwork::Error
// (a walk that does not advance, an unreachable path). It only reads the
// model, so several walks can be generated from one model in parallel.
#include <legwork/walkcycle/cycle.hpp>
#include <legwork/walkcycle/legs.hpp>
#include <legwork/walkcycle/offline/path.hpp>

#include <vector>

namespace legwork::walkcycle {

// Longest walk walk_path() makes (frames): it holds the whole motion with
// its labels and headings (about 2.1 KB a frame for the 31-joint CMU
// skeleton), so this bounds a walk near 1.1 GB: 500,000 frames are 5.8 hours
// at 24 fps, about 41,000 steps of the shipped walks.
inline constexpr int kMaxWalkFrames = 500'000;

struct WalkOptions {
  double fps = 0;              // output rate; 0 = the walk's own rate
  RootMotion root = RootMotion::Smooth;
  // Smooth root: a leg may straighten to this fraction of its length (hip to
  // ankle); beyond, the ankle target is pulled in smoothly (soft limit: the
  // knee never locks or hyper-extends; the foot may then slide).
  double soft_reach = 0.98;
  // Smooth root: a stance foot keeps the yaw it landed with while its heel is
  // down and turns on its ball as the heel rises (false: it turns with the
  // body about its pivot, twisting in place, as the pivoting plan has it).
  bool turn_on_ball = true;
  // Stairs: the steps on the flight are shortened to the treads (one tread
  // per step, see stair_stride); false keeps the walk's own stride.
  bool fit_stairs_stride = true;
  double lookahead_steps = 1.0;  // heading lead along the path, in step lengths
  bool stop = true;            // end in the standing pose at the path's end
  int max_steps = 100000;      // safety limit
  int max_frames = kMaxWalkFrames;  // longer walks are refused before anything is allocated
  // Walks again aiming past a miss of the path's end (> 1 cm), at most this
  // many times; the closest walk is kept (0: walk once).
  int end_iterations = 6;
  int steps = -1;              // > 0: walk exactly this many steps, the stop step included, ignoring
                               // the path's end (0 is rejected: a walk takes at least one step)
};

// What each output frame's interval (frame-1, frame] pivots on.
struct FrameLabel {
  int step = 0;
  bool left_stance = true;
  Pivot pivot = Pivot::Heel;
  bool stopping = false;  // in the stop step or the final hold
};

// Where a stance foot was planted (world, floor).
struct Footstep {
  Vec3 heel = Vec3::Zero();
  Vec3 ball = Vec3::Zero();
  double heading = 0;  // radians about y, 0 = facing +z
  bool left = true;
  int step = 0;
  int frame = 0;  // output frame where it takes the weight
};

struct WalkResult {
  Motion motion;                   // world-space walk
  std::vector<FrameLabel> labels;  // per frame (label of frame 0 = frame 1's)
  std::vector<double> heading;     // per frame, radians
  std::vector<Footstep> footsteps;
  int steps = 0;                   // steps taken, the stop step included
  double step_length = 0;          // straight-walk advance per step, metres
  double path_length = 0;          // metres; with WalkOptions::steps, the length walked along the path
  double end_distance = 0;         // final root (floor) distance to the path's end (with steps: to the path)
  Vec3 end_position = Vec3::Zero();  // final root on the floor (world)
  double end_heading_error = 0;    // final heading minus the path's end tangent, radians (+ = left of it)
  double travel = 0;               // floor distance from the first root position to the last, metres
  double max_path_deviation = 0;   // largest root distance from the path, metres
  double turning = 0;              // net heading change, radians (+ = to the left)
  double turning_abs = 0;          // sum of |heading changes| between steps, radians
  RootMotion root = RootMotion::Smooth;  // how the root travelled
  Ground ground;                         // the ground walked on (the path's)
  // Smooth root only. A foot out of its leg's reach (WalkOptions::soft_reach)
  // first rolls on the floor - about the ball when it trails the hip (heel
  // up), about the heel when it leads (toes up) - which keeps it planted:
  // the largest roll, radians; where rolling is not enough the pelvis drops,
  // smoothly (the largest drop, metres). What remains out of reach is pulled
  // in by the soft limit (the foot may slide): the largest hip-to-ankle
  // distance asked of a leg, as a fraction of its length, and the frames
  // where it exceeded the soft reach (soft_reach, or the keys' own if straighter).
  double foot_roll_max = 0;
  double pelvis_drop_max = 0;
  double leg_reach_max = 0;
  int reach_limited_frames = 0;
  // Smooth root: the most a foot was lifted straight up because a heel, ball
  // or toe tip would have gone into the ground (the plan's blend into the
  // standing pose, the spline between keys, a riser in a swing), metres.
  double ground_lift_max = 0;
  // Stairs: the stride the steps on the flight were shortened to (metres; 0
  // when the walk kept its own, see stair_stride).
  double stairs_stride = 0;
};

// Stairs (issue 14): the walk's stride fitted to the treads - one tread per
// step (several steps per tread if a tread is deeper than the walk's
// stride) - by blending the cycle towards the standing pose by `weight`
// (its steady travel per step is then `stride`, solved by bisection), on the
// footsteps that land between the first and last riser along the path.
// weight = 0 (no change) on other grounds or when the stride already fits.
struct StairStride {
  double stride = 0;        // metres per step on the flight
  double weight = 0;        // of the standing pose in the cycle, 0..1
  double first_riser = -1;  // arc length along the path of the first and last riser (-1: none on the path)
  double last_riser = -1;
};
StairStride stair_stride(const CycleModel& m, const Path& path);

// Straight-walk advance per step of the cycle (metres); the walk's stride.
double step_length(const CycleModel& m);

// Output frames a walk is expected to have (opt.steps steps, or the path's
// length at the cycle's stride), before it is made; walk_path() refuses one
// above opt.max_frames with this figure.
double expected_walk_frames(const CycleModel& m, double path_length, const WalkOptions& opt = {});

WalkResult walk_path(const CycleModel& m, const Path& path, const WalkOptions& opt = {});

}  // namespace legwork::walkcycle
