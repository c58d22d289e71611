#pragma once
// Full-body IK from a headset and two hand controllers (a VRIK-style
// baseline). Given the head's position and orientation and both hands'
// positions and orientations, it places the whole body:
//   - torso: pelvis and spine hang under the head (neck/torso model); when the
//     head drops the legs fold first (crouch), then the torso leans forward;
//     the chest turns toward the head's and hands' heading, the pelvis follows;
//   - head: exact position and orientation; the neck shares the turn;
//   - arms: clavicles help on long reaches, two-bone IK puts the wrists on the
//     controllers (exact whenever the target is within reach) with elbow poles
//     down, back and out like a relaxed arm;
//   - legs: feet stay planted under the hips; a foot steps (VRIK's
//     "locomotion") when the centre of mass leaves the support area, when it
//     drifts too far from its place under the hip, or when the body turns;
//     steps are predicted from the body's velocity, with a step height and
//     speed.
// The per-frame contract (docs/architecture.md): Settings -> make_model()
// builds an immutable Model (copies the skeleton; may throw) shared by any
// number of avatars; State is one avatar; update() reads the head and both
// hands of a TrackerFrame, allocates nothing and never throws.
// Model space = world, metres, y up, faces +z.
#include <legwork/core/info_fields.hpp>
#include <legwork/core/motion.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/ik/two_bone.hpp>

#include <array>
#include <span>
#include <vector>

namespace legwork::ik {

// Options of the full-body IK avatar (metres, seconds, radians).
struct Settings {
  double floor_height = 0.0;        // metres; the VR play-area floor
  // Crouch: fraction of a head drop taken by the legs (the rest by a forward
  // lean), and the lowest pelvis height as a fraction of its standing height.
  double crouch_leg_share = 0.8;
  double min_pelvis_fraction = 0.5;
  double pelvis_lean_share = 0.35;    // of the torso lean done at the hips
  double hands_heading_weight = 0.3;  // chest heading: head vs hands direction
  double pelvis_turn_rate = 8.0;      // 1/s, pelvis yaw following the chest
  double neck_share = 0.3;            // of the head's turn relative to the chest taken by the neck
  double clavicle_reach = 0.5;        // radians: most a clavicle swings to bring a hand within reach
  double body_reach = 1.2;            // radians: most the body swings about the head when a clavicle is not enough
  // Locomotion (VRIK names): stepping when the centre of mass is farther than
  // step_threshold outside the segment between the feet, or a foot is farther
  // than foot_distance_threshold from its place, or turned more than
  // step_angle_threshold (radians) from the pelvis.
  double balance_head_weight = 0.75;  // balance point = this share of the head + the rest of the pelvis
  double step_threshold = 0.10;
  double foot_distance_threshold = 0.22;
  double step_angle_threshold = 0.7;
  double step_speed = 3.5;                            // m/s of foot travel (at least)
  double swing_speed_ratio = 2.0;                     // foot travel speed / body speed when faster
  double min_step_time = 0.14, max_step_time = 0.40;  // seconds
  double step_height = 0.09;                          // metres at mid-swing
  double velocity_lead = 1.0;                         // landing predicted this many step times ahead
  double max_step_length = 1.2;                       // metres
};

class Model {
 public:
  // The skeleton of the output pose (a copy of make_model's).
  const Skeleton& skeleton() const { return skel_; }
  const Settings& settings() const { return settings_; }

  // Rest measurements (identity rotations), metres.
  double standing_head_height() const { return head_height_; }
  double standing_pelvis_height() const { return pelvis_height_; }
  double torso_length() const { return torso_length_; }  // pelvis to head, vertical

 private:
  friend Model make_model(const Skeleton&, const Settings&);
  friend struct Solver;  // the update stages (full_body.cpp)
  Model() = default;
  Skeleton skel_;
  Settings settings_;
  TwoBoneChain arm_[2], leg_[2];
  int pelvis_ = -1, head_ = -1, clavicle_[2] = {-1, -1};
  std::vector<int> spine_;  // spine chain, bottom up
  std::vector<int> neck_;   // neck joints below the head, bottom up
  double head_height_ = 0, pelvis_height_ = 0, torso_length_ = 0;
  std::array<Vec3, 2> foot_offset_{};  // ankle relative to pelvis, horizontal (x, 0, z)
  double ankle_height_ = 0;            // rest ankle height above the sole
  double leg_length_ = 0, arm_length_ = 0;
};

// Builds the model for `skel` (copied). Throws legwork::Error if the skeleton
// lacks head, neck, pelvis, arm or leg roles, or its rest pose is not an
// upright body.
Model make_model(const Skeleton& skel, const Settings& settings = {});

// One avatar: what it remembers between frames, plus a scratch FK buffer
// sized for the model (allocated here, never in update()).
struct State {
  explicit State(const Model& model);

  struct Foot {
    Vec3 position = Vec3::Zero();  // ankle, model space
    double yaw = 0;
    bool stepping = false;
    double step_time = 0, step_duration = 0;
    Vec3 from = Vec3::Zero();
    double from_yaw = 0;
  };
  FrameClock clock;
  bool initialized = false;  // feet placed from a usable head
  std::array<Foot, 2> feet;
  double chest_yaw = 0, pelvis_yaw = 0;
  Vec3 previous_head = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();  // smoothed horizontal head velocity, m/s
  DevicePose held_head;          // last usable head (used while the head is lost)
  int steps_taken = 0;
  std::vector<Transform> scratch;  // model-space FK buffer
};

// Back to a new avatar (clock included); the next frame starts it.
void reset(const Model& model, State& state);

// Per-frame diagnostics.
struct Info {
  int steps_taken = 0;                       // steps completed since the avatar started
  std::array<bool, 2> stepping{false, false};  // [kLeft], [kRight]: foot in the air
  double chest_yaw = 0, pelvis_yaw = 0;      // radians about y, 0 = facing +z
  double lean = 0;                           // torso lean from upright, radians
  bool head_tracked = false;                 // false: the last usable head was held
  std::array<bool, 2> hand_tracked{false, false};  // false: that arm relaxes
};

// Solves one frame: the head is placed exactly on frame.head(), the wrists on
// frame.hand(kLeft/kRight) when within reach, legs step under the body.
// `out` must have the model skeleton's joint count; every joint is written
// (unless Rejected). Time from state.clock: Rejected leaves state and `out`
// untouched; Restarted re-places the feet (a new start) and solves the frame.
// A lost or unusable head holds the last usable one (a standing rest body at
// the origin before any), a lost hand relaxes its arm: both are Degraded.
UpdateStatus update(const Model& model, const TrackerFrame& frame, State& state, PoseRef out, Info* info = nullptr);

// This frame's Info as named fields (InfoFields: the server's pose "info",
// the C API's lw_avatar_info_field); allocates nothing.
void describe(const Info& info, InfoFields& out);

}  // namespace legwork::ik
