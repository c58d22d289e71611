#pragma once
// Figures that check a walk: stance-foot slip, loop seam continuity, joint
// arcs and their smoothness, foot heights at the key poses. Offline (they
// allocate); all positions in metres, model or world space as stated.
#include <legwork/walkcycle/offline/walk.hpp>

#include <array>
#include <span>
#include <vector>

namespace legwork::walkcycle {

// (kFootDownTolerance, the height within which a foot point is down: legs.hpp.)

// Stance slip: for every pivot phase (one stance foot pivoting on its heel or
// on its ball), the largest horizontal distance the pivot point moves from
// where it was when the phase began, measured by full FK of the output frames,
// while it is on the ground (`ground`; a pivot lifted more than
// kFootDownTolerance - a heel rising early onto the ball, a heel that strikes
// late - is anchored again where it comes down).
struct SlipReport {
  double max_mm = 0;
  double mean_mm = 0;  // mean over phases of each phase's maximum
  int phases = 0;
  int worst_step = -1;
  std::vector<double> per_step_mm;  // max per step
};
SlipReport measure_stance_slip(const CycleModel& m, const Motion& walk, std::span<const FrameLabel> labels,
                               const Ground& ground = Ground{});

// The root's horizontal speed while cruising (steps after the first, before
// the stop step): frame-to-frame speed min / mean / max (m/s) and the largest
// horizontal acceleration (m/s^2, difference of successive velocities).
// A walk too short to cruise reports frames = 0 and zeros. The pelvis's
// (root joint's) vertical smoothness is measured over the whole walk (start,
// stairs and stop included): the largest vertical speed (m/s, frame-to-frame
// difference) and acceleration (m/s^2, second difference).
struct RootMotionReport {
  double speed_min_mps = 0;
  double speed_mean_mps = 0;
  double speed_max_mps = 0;
  double accel_max_mps2 = 0;
  int frames = 0;  // cruising frames measured
  double vertical_speed_max_mps = 0;
  double vertical_accel_max_mps2 = 0;
};
RootMotionReport measure_root_motion(const Motion& walk, std::span<const FrameLabel> labels);

// Feet against the ground (flat or uneven), by full FK of every frame.
struct GroundContactReport {
  double penetration_mm = 0;    // deepest a heel, ball or toe tip goes below the ground (0 = never)
  int penetration_frame = -1;
  double stance_float_mm = 0;   // highest the stance foot's lowest point (heel, ball, toe tip) is above the ground
  int float_frame = -1;
};
GroundContactReport measure_ground_contact(const CycleModel& m, const Motion& walk, std::span<const FrameLabel> labels,
                                           const Ground& ground);

// The stance foot on turns (issue 14, item 2): a foot point (heel, ball) is
// down while it is within kFootDownTolerance of the ground. For every stance
// (the weight-bearing foot of one step), the largest horizontal distance the
// heel and the ball move from where they came down while they stay down
// (slip), and the largest change of the foot's yaw (heel-to-ball direction)
// while both are down (twist: a flat foot turning in place). A foot that
// turns on its ball once the heel is up shows neither.
struct FootTurnReport {
  double heel_slip_mm = 0;
  double ball_slip_mm = 0;
  double twist_deg = 0;   // largest yaw change while flat
  int worst_step = -1;    // step of the largest twist
  double turn_on_ball_deg = 0;  // largest yaw change of a stance foot while only its ball is down
};
FootTurnReport measure_foot_turning(const CycleModel& m, const Motion& walk, std::span<const FrameLabel> labels,
                                    const Ground& ground);

// Feet on stairs (Ground::Kind::Stairs; zeros on other grounds): for every
// stance, where the stance foot's ball is while it is down (within
// kFootDownTolerance of the ground). ball_margin_mm = the smallest distance
// of a ball that is down from a tread's edge (a riser's line), over all
// stances; treads_per_step_max = the most treads (risers) between the balls
// of two successive stances (1 = one tread per step; 2 = every other tread).
struct TreadReport {
  double ball_margin_mm = 0;
  int treads_per_step_max = 0;
  int stances = 0;  // stances whose ball came down
};
TreadReport measure_treads(const CycleModel& m, const Motion& walk, std::span<const FrameLabel> labels, const Ground& ground);

// Seam of the in-place loop: every joint's model-space position and velocity
// just before frame N (left limit, quadratic extrapolation) against frame 0
// (right limit). Largest difference over joints: metres and metres/second.
struct SeamReport {
  double position_m = 0;
  double velocity_mps = 0;
};
SeamReport measure_loop_seam(const CycleModel& m);

// A joint's model-space path over one in-place cycle, `samples_per_frame`
// points per frame (frame N left out: the polyline is closed).
struct Arc {
  int joint = -1;
  int samples_per_frame = 1;
  std::vector<Vec3> points;
  std::vector<int> key_indices;  // points at the 8 key poses of the cycle
};
Arc trace_arc(const CycleModel& m, int joint, int samples_per_frame = 1);

// Arc smoothness. The turning angle at each point (ignoring points where the
// joint barely moves) should change gradually; a key pose that breaks the
// arc shows as a jump. jerk_ratio = largest |third difference| of the
// points over the median one (a smooth loop stays low; a key pose that
// kinks the arc raises it, and jerk_frame says where).
struct ArcSmoothness {
  double extent_m = 0;  // bounding-box diagonal of the arc (tiny arcs: ratios mean little)
  double max_curvature_jump_deg = 0;
  double jump_frame = 0;
  double jerk_ratio = 0;
  double jerk_frame = 0;
};
ArcSmoothness arc_smoothness(const Arc& arc);

// Lowest foot point (heel, ball, toe tip) above the floor at each of the
// five key poses of the step, metres (0 = touching; < 0 = below the floor).
std::array<double, kKeyCount + 1> key_foot_heights(const CycleModel& m);

// The same lowest foot point over the whole in-place cycle (4 samples per
// frame): the minimum (metres, negative = below the floor; >= 0 with
// floor_clamp) and where, and how far the floor clamp had to lift the root
// (how far the spline alone would dip a foot below the floor between keys).
struct FloorReport {
  double lowest_m = 0;
  double at_frame = 0;
  double max_lift_m = 0;
  double lift_frame = 0;
};
FloorReport cycle_floor_contact(const CycleModel& m);

}  // namespace legwork::walkcycle
