#pragma once
// Runtime walking, frame by frame: the same no-slip pivoting as walk_path,
// but steered live (e.g. by a game's stick) instead of along a known path.
//
// The per-frame contract (docs/architecture.md): Settings -> make_model()
// copies the cycle into an immutable Model shared by any number of
// characters; State is one character; update() allocates nothing, throws
// nothing and touches only the state and the output pose.
//
// Input: the TrackerFrame's absolute time (FrameClock rules; the first
// accepted frame starts the walk at time 0 of the cycle, each later one
// advances it by the seconds since the last, at the walk's rate) and the
// heading to steer to = the yaw of frame.head().rotation when it is usable (a
// game passes its stick direction as a head rotation about +y); otherwise the
// previous heading asked for is kept (Degraded).
// The heading asked for is taken once per step, at the middle of the previous
// step, limited to Settings::max_turn_per_step, and blended in over the next
// step (document 001: no heading keys in the first half of step n and the
// second half of step n-1); every turn is applied about the planted pivot.
//
// Root (Settings::root, issue 14 item 1). The pivoting walk above is the
// plan: it keeps the stance foot still by dragging the root, which lunges and
// stalls twice per step. With RootMotion::Smooth (the default) the root
// instead travels at the cycle's mean velocity (its stride over its time,
// turned with the heading) plus the pelvis's own offsets from the keys: the
// plan's floor offset minus its drag, a function of the cycle's phase
// tabulated by make_model from a straight walk, followed by a first-order
// follower (time constant half a step) that absorbs what turns change; on a
// straight walk the root is exactly the plan's mean travel. Both legs are
// then solved by two-bone IK (legs.hpp) so each ankle is where the plan put
// it (the stance foot stays planted, the swing foot keeps its path); a foot
// out of reach rolls on its ball or heel, then the pelvis drops (the drop
// the straight walk needs at that phase, spread over a quarter step and
// averaged over half a step, tabulated), then the soft limit pulls the ankle
// in (Info::reach_limited). No foot point goes below the floor (the plan is
// walked without the cycle's floor lift; a dipping foot is lifted by its leg).
// On turns each stance foot keeps the yaw it landed with while its heel is
// down and turns on its ball as the heel rises (Settings::turn_on_ball;
// StanceTurn in legs.hpp, the same code as walk_path's), instead of twisting
// with the body about its pivot.
// RootMotion::Pivot is document 001's root, unchanged.
#include <legwork/core/info_fields.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/walkcycle/cycle.hpp>
#include <legwork/walkcycle/ground.hpp>
#include <legwork/walkcycle/legs.hpp>

#include <array>
#include <vector>

namespace legwork::walkcycle {

struct Settings {
  double max_turn_per_step = deg2rad(30.0);  // radians of heading change per step, at most
  Vec3 start_position = Vec3::Zero();        // floor point under the root at the start (y ignored), metres
  double start_heading = 0;                  // radians about y at the start, 0 = facing +z
  RootMotion root = RootMotion::Smooth;      // Smooth: even travel, legs by IK; Pivot: document 001's root
  // Smooth root: a stance foot keeps the yaw it landed with while its heel is
  // down and turns on its ball as the heel rises (StanceTurn, as walk_path);
  // false: it turns with the body about its pivot (twisting in place).
  bool turn_on_ball = true;
  double soft_reach = 0.98;                  // smooth root: fraction of a leg's length it may straighten to, (0, 1]
  // Smooth root: the ground walked on (a slope, a height field or stairs,
  // the same type as a path file's "ground"). The feet are put on it by the
  // legs' IK (fit_to_ground, as walk_path), the pelvis rises by the ground
  // under the feet, followed smoothly (two first-order stages of a quarter
  // step with their lag compensated: a constant grade is followed exactly).
  // On stairs each footstep is planted flat on a tread (fit_on_tread, as
  // walk_path): where the swing foot will land is predicted from the cycle
  // and the heading (exact once the step's heading is latched, at mid-swing,
  // when the plant is fixed), the swing carries the foot up early or down
  // late, the pelvis follows the lower foot's height and drops as far as
  // the legs need to reach the treads (both followed smoothly).
  Ground ground;
  // Stairs: the cycle's rate while a foot's plant is higher or lower than
  // the other's (people climb and descend at a slower cadence than they walk
  // on the flat), reached smoothly (over about a step); (0, 1].
  double stairs_cadence = 0.8;
};

class Model {
 public:
  const Skeleton& skeleton() const { return cycle_.skeleton; }  // the output pose's skeleton
  const Settings& settings() const { return settings_; }
  // The walked cycle: a copy of make_model's, without its floor lift for the
  // smooth root (its legs keep the feet above the floor).
  const CycleModel& cycle() const { return cycle_; }

  // Smooth root tables over one cycle, `samples_per_frame` per cycle frame
  // (entry i at cycle time i / samples_per_frame, the last equal to the first).
  static constexpr int samples_per_frame = 8;
  struct SmoothRoot {
    Vec3 velocity = Vec3::Zero();  // the plan's mean floor travel per cycle frame, character frame (heading 0)
    std::vector<Vec3> drag;        // the plan's floor offset minus its mean travel, character frame, metres
    std::vector<double> drop;      // pelvis drop, metres (>= 0)
    std::array<LegIk, 2> legs;     // right, left
    LegJoints joints;              // the joints the legs' IK needs
    // Stairs only: the straight walk's travel of the swing foot's heel from
    // each sample to its landing (the next step's start), character frame,
    // metres; and each foot's (right, left) ball and toe tip ahead of its heel
    // standing flat, metres.
    std::vector<Vec3> to_landing;
    std::array<std::array<double, 2>, 2> foot_reach{};
  };
  const SmoothRoot& smooth_root() const { return smooth_; }

 private:
  friend Model make_model(const CycleModel&, const Settings&);
  Model() = default;
  CycleModel cycle_;
  Settings settings_;
  SmoothRoot smooth_;
};

// Copies `cycle` (and tabulates the smooth root). Throws legwork::Error on an
// unusable cycle (no frames, a non-positive rate), non-finite settings or a
// soft_reach outside (0, 1].
Model make_model(const CycleModel& cycle, const Settings& settings = {});

// One walking character.
struct State {
  explicit State(const Model& model);

  FrameClock clock;
  bool started = false;         // the first frame has been consumed
  Vec3 start_position = Vec3::Zero();  // where the next start begins (floor)
  double start_heading = 0;
  double desired_heading = 0;   // last heading asked for, radians
  double time = 0;              // cycle frames since the start (contact of the left foot)
  double heading_from = 0;      // radians about y, 0 = facing +z
  double heading_to = 0;
  int decided_step = 0;         // last step whose heading has been latched
  double heading = 0;           // current heading, radians
  Vec3 offset = Vec3::Zero();   // world = yaw(heading) * in-place + offset (floor, y = 0)
  std::array<Vec3, 4> feet{};   // in-place heel/ball of right/left foot at `time`
  Vec3 smooth = Vec3::Zero();   // smooth root: world = yaw(heading) * in-place + smooth (floor, y = 0)
  std::array<StanceTurn, 2> turn{};  // smooth root: right, left foot turning on its ball (legs.hpp)
  std::array<double, 2> rise{};      // smooth root on uneven ground: the pelvis's rise, two follower stages, metres
  bool rise_started = false;
  // Stairs: each foot's (right, left) plant - the tread it stands on (or
  // last stood on) and the one its swing lands on: height and move along
  // the stairs (fit_on_tread), metres.
  struct Plant {
    double height = 0, move = 0;
  };
  std::array<Plant, 2> plant_on{}, plant_next{};
  std::array<bool, 2> stance_was{};  // the foot bore the weight last frame
  std::array<bool, 2> next_fixed{};  // its landing is fixed (the step's heading is latched)
  bool plants_started = false;       // the plants are set (the first frame puts each foot where it stands)
  std::array<double, 2> drop_stage{};  // stairs: the pelvis drop following the legs' need, two follower stages, metres
  bool drop_started = false;
  double rate = 1;                   // stairs: the cycle's rate (Settings::stairs_cadence on the flight)
  // Scratch (sized once, no meaning between frames): FK of the plan's pose and of the solved one.
  std::vector<Transform> plan_space, model_space;
};

// A new character at the settings' start (clock included).
void reset(const Model& model, State& state);
// A new character whose walk will start above `position` (floor point, y
// ignored) facing `heading` (radians); the next accepted frame starts it.
void reset(const Model& model, State& state, const Vec3& position, double heading);

struct Info {
  int step = 0;                 // step index since the start (0 = the left foot's first stance)
  double cycle_time = 0;        // cycle frames since the start
  double heading = 0;           // current heading, radians
  double desired_heading = 0;   // heading asked for, radians
  bool left_planted = true;     // the stance foot this frame
  Pivot pivot = Pivot::Heel;    // which point of it the body pivots on
  // Smooth root only:
  double pelvis_drop = 0;       // metres the pelvis is lowered so the legs reach
  double ground_rise = 0;       // metres the pelvis is raised by the ground under the feet
  double cadence = 1;           // the cycle's rate (1; Settings::stairs_cadence on stairs)
  double foot_roll = 0;         // largest roll of a foot out of reach, radians (either foot)
  bool reach_limited = false;   // a leg needed more than soft_reach (its foot was pulled in)
};

// One frame: Rejected (time not usable) leaves state and `out` untouched;
// Restarted (the stream's clock restarted) keeps walking from where the
// character is, without advancing; otherwise the walk advances by the frame's
// dt. `out` must have the model skeleton's joint count; the world pose is
// written.
UpdateStatus update(const Model& model, const TrackerFrame& frame, State& state, PoseRef out, Info* info = nullptr);

// This frame's Info as named fields (InfoFields: the server's pose "info",
// the C API's lw_avatar_info_field); allocates nothing.
void describe(const Info& info, InfoFields& out);

}  // namespace legwork::walkcycle
