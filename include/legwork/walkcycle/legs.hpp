#pragma once
// The smooth root's legs (issue 14, item 1), shared by the live walker
// (walker.hpp) and walk_path (offline): the root travels smoothly and
// two-bone leg IK puts each ankle where the pivoting plan had it. Runtime
// code: no allocation, no exceptions. Positions are model = world space of
// the pose being solved, metres.
#include <legwork/core/fk.hpp>
#include <legwork/core/rotation.hpp>
#include <legwork/ik/two_bone.hpp>
#include <legwork/walkcycle/cycle.hpp>
#include <legwork/walkcycle/ground.hpp>

#include <algorithm>
#include <array>
#include <span>

namespace legwork::walkcycle {

// How the root travels.
enum class RootMotion : unsigned char {
  // The root travels at a smooth speed (the pivoting root's drag of the
  // planted foot removed) with the pelvis's own offsets from the keys, and
  // both legs are solved by two-bone IK so each ankle is where the pivoting
  // walk put it: the stance foot stays planted, the swing foot keeps its path.
  Smooth,
  // Document 001's method: the root is pushed so the stance foot's pivot
  // stays put (the root lunges and stalls twice per step); no IK.
  Pivot,
};

// A foot point (heel, ball) is on the ground while it is within this height
// above it (a shoe sole's give); above, it is in the air and cannot slip.
inline constexpr double kFootDownTolerance = 0.005;  // metres

// A rigid horizontal move of one foot of the plan: turned by `angle` about the
// vertical through the plan's point `pivot`, then moved by `offset`
// (horizontal). The identity leaves the plan's foot alone.
struct FootHold {
  double angle = 0;
  Vec3 pivot = Vec3::Zero();
  Vec3 offset = Vec3::Zero();
  double lift = 0;  // stairs: the height the foot is planted at (or carried at in the swing), metres
  Vec3 tread = Vec3::Zero();  // stairs: the part of `offset` that moves the foot onto its tread
  // A stance foot already pivoting on its ball (its heel up before the pass
  // key): the ground's slope turns it about the ball, not the heel.
  bool on_ball = false;
  // (One rotation built per call, none for a zero angle: the identity
  // quaternion's products are exact, so the result is the same to the bit.)
  Vec3 apply(const Vec3& x) const { return angle == 0 ? moved(x - pivot) : moved(yaw_rotation(angle) * (x - pivot)); }
  Transform apply(const Transform& t) const {
    if (angle == 0) return {t.rotation.normalized(), moved(t.translation - pivot)};
    const Quat q = yaw_rotation(angle);
    return {(q * t.rotation).normalized(), moved(q * (t.translation - pivot))};
  }

 private:
  Vec3 moved(const Vec3& turned) const { return pivot + turned + offset + Vec3(0, lift, 0); }
};

// The stance foot turns on its ball, not in place (issue 14, item 2), for
// walk_path's smooth root and the live walker alike. The pivoting plan turns
// the whole body, stance foot included, about the planted pivot: a flat foot
// twists on its heel and its heel slides round the ball. Here each stance
// foot keeps the yaw it landed with while its heel is down and turns to the
// plan's yaw on its ball as the heel rises (fully once the heel is 2 cm up;
// at the latest over the last quarter of the stance), its pivot (heel, then
// ball) held where it was. Once the foot leaves the ground the offset this
// leaves is faded out over the middle of the swing, so it lands on the
// plan's footprint. One per foot, fed every frame in order.
struct StanceTurn {
  struct Frame {
    Vec3 heel = Vec3::Zero(), ball = Vec3::Zero();  // the plan's (world; y above its flat floor)
    bool stance = false;         // this foot bears the weight
    Pivot pivot = Pivot::Heel;   // the plan's pivot of the stance foot
    double step_fraction = 0;    // how far through its step (0 at the step's start, 1 at its end)
    bool stopping = false;       // in the stop step or the final hold
    double time = 0;             // now, in any unit...
    double step_time = 1;        // ...and a step's duration in it
  };
  // The hold of this frame (the plan's foot moved by it is where the foot goes).
  const FootHold& advance(const Frame& f);

  bool started = false;
  bool stance = false;
  Pivot pivot = Pivot::Heel;
  double landed_yaw = 0, turned = 0;  // the yaw it landed with; how far it has turned to the plan's (0-1)
  double left_ground = -1;            // time the foot left the ground
  Vec3 lift_off = Vec3::Zero();       // its offset from the plan then
  Vec3 anchor = Vec3::Zero();         // where the stance foot's pivot is held (floor)
  Vec3 heel = Vec3::Zero(), ball = Vec3::Zero();  // the plan's, previous frame
  FootHold hold;
};

struct LegIk {
  ik::TwoBoneChain chain;
  double length = 0;  // thigh + shin, metres
};

// The joints the legs' IK reads and writes in model space: both feet's
// chains (root ... ankle) and their toes, parents first; `all` when a toe
// does not hang from its ankle (then every joint).
struct LegJoints {
  std::array<int, 34> joints{};
  int count = 0;
  bool all = false;
  std::span<const int> list() const { return {joints.data(), static_cast<std::size_t>(count)}; }
};
LegJoints leg_joints(const CycleModel& m);

// FK of those joints only, to the same values forward_kinematics gives them
// (the other entries of `g` are left as they were).
void leg_kinematics(const Skeleton& s, const LegJoints& legs, ConstPoseRef pose, std::span<Transform> g);

// g[j] = before[j] moved by `shift` for those joints (the moved pose's FK).
void shift_legs(const LegJoints& legs, std::span<const Transform> before, const Vec3& shift, std::span<Transform> g);

// The left or right leg's chain and length from a pose's FK `g`.
LegIk leg_of(const Skeleton& s, bool left, std::span<const Transform> g);

// Where the leg can put the ankle: the target pulled towards the hip so the
// leg never straightens fully. Up to `soft` of its length the target is kept;
// beyond, the distance approaches the full length exponentially (the knee
// straightens smoothly instead of snapping). Returns the distance asked for,
// as a fraction of the leg's length.
double soften_reach(const Vec3& hip, const LegIk& leg, double soft, Vec3& target);

// A foot whose ankle is out of the leg's reach rolls on the floor instead of
// dragging: the stance foot about its ball once it pivots on the ball (the
// heel rises; while it pivots on the heel it does not roll: rolling would
// move the ball it is about to pivot on); the other foot (`stance` null)
// about its ball when it trails the hip (the heel rises, as at toe-off),
// about its heel when it leads (the toes rise, as at heel strike). The
// rolling point stays where it was; the smallest roll (at most 60 degrees
// either way) that brings the ankle back to `reach` of the hip, or if none
// does the one that brings it closest. `ankle` is updated in place. Returns
// the angle, radians.
double roll_foot(const FootPivots& foot, const Vec3& hip, double reach, const Vec3& forward, const Pivot* stance,
                 Transform& ankle);

// Pelvis drop that brings `hip` within `reach` of `target` (0 if it is).
double drop_to_reach(const Vec3& hip, const Vec3& target, double reach);

// The toe's model transform after the leg's IK moved the ankle (the IK
// updates the chain only; full FK if the toe does not hang from the ankle).
void update_toe(const Skeleton& s, const FootPivots& foot, ConstPoseRef pose, std::span<Transform> g);

// How far the foot's lowest point (heel, ball, toe tip) is below the ground
// (`height(point)` = the ground's height under it), metres (0 if none is);
// `g` holds the pose's FK.
template <class GroundHeight>
double depth_below(const Skeleton& s, const FootPivots& foot, std::span<const Transform> g, const GroundHeight& height) {
  const Transform& a = g[static_cast<std::size_t>(foot.ankle)];
  auto below = [&](const Vec3& p) { return height(p) - p.y(); };
  double d = std::max(below(a.apply(foot.heel_local)), below(a.apply(foot.ball_local)));
  if (foot.toe >= 0) d = std::max(d, below(end_site_position(s, g, foot.toe)));
  return std::max(0.0, d);
}

// One frame of the smooth root, as both legs see it: the plan's FK
// (`before`), the shift the root moved by (the moved pose's FK is `g`), the
// walking direction, and the soft limit of the legs' reach.
struct LegFrame {
  const Skeleton& skeleton;
  const Ground& ground;
  std::span<const Transform> before;
  Vec3 shift;
  Vec3 forward;
  double soft_reach;
};

// What placing one leg did.
struct LegPlacement {
  double drop = 0;      // pelvis drop that would bring the ankle within reach
  double roll = 0;      // the foot's roll, radians
  double reach = 0;     // the reach asked for, fraction of the leg's length
  double lift = 0;      // how far the foot was lifted out of the ground, metres
  bool limited = false; // the soft limit pulled the ankle in
};

// One leg of the smooth root (the live walker's and walk_path's): the plan's
// ankle moved by the foot's `hold`, fitted to the ground, rolled if out of
// reach (`pivot`: the stance foot's, null for the other foot), pulled in by
// the soft limit (as straight as the keys had it, or soft_reach, whichever
// is more). With `apply`, the leg is solved by two-bone IK (the knee points
// where it did), the toes keep their world rotation (or turn with the
// ground), and a foot point below the ground lifts the foot straight up (no
// slip, no penetration); without, only measures.
LegPlacement place_leg(const LegFrame& frame, const LegIk& leg, const FootPivots& foot, const FootHold& hold,
                       const Pivot* pivot, bool apply, PoseRef pose, std::span<Transform> g);

}  // namespace legwork::walkcycle
