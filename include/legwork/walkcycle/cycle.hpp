#pragma once
// The full walk cycle: the step's key poses, mirrored into the second step,
// placed on the cycle's frames and interpolated with a loop-continuous spline.
//
// build_cycle() is the offline builder (allocates, validates, may throw);
// CycleModel is immutable afterwards and sample_cycle() is the runtime call
// (no allocation, no exceptions, thread-safe on a shared model).
//
// Interpolation: each joint's rotation keys are expressed as rotation vectors
// (quaternion logs) relative to the joint's mean key rotation and joined by a
// periodic cubic Hermite spline (tangents from the neighbouring keys, the
// three-point derivative), so the loop is C1: frame N equals frame 0 and the
// velocity does not jump at the seam. Root offsets use the same spline.
// Mirroring reflects about the sagittal (yz) plane with legwork::mirror_pose
// conventions, so step 2 at frame f + N/2 is exactly the mirror of step 1 at f.
#include <legwork/walkcycle/keys.hpp>

#include <array>
#include <span>
#include <vector>

namespace legwork::walkcycle {

// Contact points of one foot, fixed in the ankle joint's frame: the heel
// (the ankle projected to the floor in the standing pose, unless the skeleton
// has no toe) and the ball (the toe-base joint projected to the floor).
struct FootPivots {
  int ankle = -1;
  int toe = -1;                // -1 if the skeleton has no toe joint
  std::array<int, 16> chain{};  // root ... ankle, joint indices
  int chain_length = 0;
  Vec3 heel_local = Vec3::Zero();  // metres, ankle frame
  Vec3 ball_local = Vec3::Zero();  // metres, ankle frame
};

enum class Pivot : unsigned char { Heel, Ball };

struct CycleModel {
  Skeleton skeleton;
  int frames_per_cycle = 24;
  double fps = 24;
  // Root height above the floor in the standing pose (metres); key-pose
  // root offsets are relative to (0, stand_height, 0).
  double stand_height = 0;
  // Frames of the contact, down, pass and up keys in the first step.
  std::array<double, kKeyCount> key_frames{};

  // Spline channels (internal layout; see sample_cycle).
  struct Channel {
    int first = 0;
    int count = 0;
    Quat ref = Quat::Identity();  // rotation channels: mean key rotation
    // Channels with the same key times share one segment lookup per sample:
    // the index into `time_groups` (-1: looked up on its own).
    int times = -1;
    // A rotation channel that never moves (one key, or every key at the mean:
    // a joint no key poses): sample_cycle writes `value`, the spline's exact
    // result at any time.
    bool fixed = false;
    Quat value = Quat::Identity();
  };
  // Key times shared by channels (the keys of a channel in the group, [first, first + count)).
  struct TimeGroup {
    int first = 0;
    int count = 0;
  };
  static constexpr int max_time_groups = 32;
  std::vector<TimeGroup> time_groups;  // at most max_time_groups
  std::vector<Channel> rotation;  // per joint
  Channel root_offset;            // Vec3 values (x side, y height, z forward)
  Channel floor_lift;             // (0, lift, 0): keeps the feet above the floor (count 0 = none)
  std::vector<double> key_time;   // cycle frames, sorted within a channel, in [0, N)
  std::vector<Vec3> key_value;    // rotation vector (radians) or offset (metres)
  std::vector<Vec3> key_slope;    // d value / d frame at the key

  // The authored key poses of the step as full poses (rest where unspecified),
  // and the next contact (mirror of contact): 5 poses, root at (side, height, forward).
  std::array<Pose, kKeyCount + 1> step_keys;
  Pose stand;  // standing pose, root at (0, stand_height, 0)
  bool floor_clamp = true;  // sample_cycle adds floor_lift (no foot below the floor)
  // The pivoting walk's travel per step, metres (straight_pivot_travel at 8
  // samples per frame, half of one cycle's; the floor lift does not change
  // it), computed by build_cycle; < 0 = not computed.
  double step_travel = -1;
  FootPivots left, right;

  double half_cycle() const { return frames_per_cycle / 2.0; }
  const FootPivots& foot(bool left_foot) const { return left_foot ? left : right; }
};

// Builds the cycle for `skel` (roles resolved: pelvis, hips, knees, ankles
// required; toes optional). Throws legwork::Error on unusable keys.
CycleModel build_cycle(const Skeleton& skel, const WalkKeys& keys);

// Local pose at cycle time `frame` (cycle frames; any real number, wrapped
// into [0, N)). Root translation = (0, stand_height, 0) + root offset (+ the
// smooth floor lift that keeps every foot point above the floor, if
// floor_clamp; it covers the dips sampled 4 times per frame).
void sample_cycle(const CycleModel& m, double frame, PoseRef out);

// The in-place loop: frames_per_cycle frames at the walk's rate (frame N,
// equal to frame 0, left out so the clip loops).
Motion bake_cycle(const CycleModel& m);

// Model-space position of a foot's heel or ball for a pose (FK of the leg
// chain only; no allocation).
Vec3 foot_point(const CycleModel& m, ConstPoseRef pose, bool left_foot, Pivot which);
// Both points of one foot at once ([heel, ball]; the same values as two foot_point calls).
std::array<Vec3, 2> heel_and_ball(const CycleModel& m, ConstPoseRef pose, bool left_foot);

// The pivoting walk straight ahead over one cycle, `samples_per_frame` steps
// per cycle frame: its floor offset (world root = in-place root + offset)
// after each step, entry 0 = zero, entry N * samples_per_frame one cycle on
// (twice the step length). Allocates (a builder, not a per-frame call).
std::vector<Vec3> straight_pivot_travel(const CycleModel& m, int samples_per_frame);

// Height of the lowest foot point (heel, ball or toe tip of either foot)
// above the floor for a pose, metres, model space (FK of the leg chains only).
double lowest_foot_height(const CycleModel& m, ConstPoseRef pose);

// Which foot carries the weight and which point it pivots on at cycle time t
// (first step: left foot, heel until the pass key, then ball).
struct StanceAt {
  int step = 0;  // floor(t / half cycle)
  bool left = true;
  Pivot pivot = Pivot::Heel;
};
StanceAt stance_at(const CycleModel& m, double frame);

}  // namespace legwork::walkcycle
