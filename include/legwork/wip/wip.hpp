#pragma once
// Walking-in-place legs: tracked ankle heights -> gait phases -> IK-target
// depths and heights (the document's equations 1-8) -> a solved avatar pose
// that walks forward along its heading.
//
// Runtime: a const WipModel (avatar + parameters, built offline by
// make_wip_model) plus a mutable WipWorkspace (made once by make_workspace);
// update() is allocation-free, exception-free and does no I/O. One workspace
// per avatar; workspaces are independent, so avatars can run on any threads.
#include <legwork/ik/two_bone.hpp>
#include <legwork/wip/gait.hpp>
#include <legwork/wip/mapping.hpp>
#include <legwork/wip/speed.hpp>
#include <legwork/wip/tracker.hpp>

#include <span>
#include <string>
#include <vector>

namespace legwork::wip {

enum class SpeedModel { StepSpeed, StepFrequency };

struct MappingParams {
  // Avatar scaling: the document's S = 0.6 m and hint 0.29 m are for a 0.8 m
  // leg; both scale with the avatar's measured leg length.
  double reference_leg = 0.8;
  double step_length = 0.6;   // S at the reference leg, m
  double user_step_height = 0.3;  // H: the user's maximum step height, m (lambda = 4H)
  // Scale each step's height by H / (the user's running apex estimate) so a
  // normal step spans the equations' whole range (0..H) and the ascending and
  // descending branches meet at the apex; false = the document's raw h.
  bool normalise_height = true;
  double lift_scale = 0.5;    // eq. 8's 0.5: avatar lift per metre of user lift
  double stop_time = 1.5;     // s of double support -> stop (legs back to neutral)
  double smoothing_tau = 0.05;  // s: exponential approach of the targets (the document's lerp)
  double body_tau = 0.05;       // s: same for the body's vertical offset
  double hint_forward = 0.29;   // m in front of the knee at the reference leg
  double knee_bend = 0.02;      // standing root lowered by this fraction of the leg (keeps knees soft)
  bool feet_flat = true;        // keep the ankle's standing model rotation
  SpeedModel speed_model = SpeedModel::StepSpeed;
  double speed_gain = 2.15;     // step-speed model gain: comfortable in-place stepping (0.15 m, 1.8 steps/s) -> ~1.3 m/s
  double stride_per_step = 0.65;  // step-frequency model, m per step
  double max_speed = 3.5;       // m/s cap
  double speed_tau = 0.3;       // s: smoothing of the forward speed
};

struct WipParams {
  SignalParams signal;
  GaitParams gait;
  MappingParams mapping;
};

// The avatar and everything derived from it. Built offline; immutable while running.
struct WipModel {
  Skeleton skeleton;
  WipParams params;
  ik::TwoBoneChain legs[2];
  Pose base_pose;            // standing pose the legs are solved from (root at the origin)
  double leg_length = 0;     // measured hip-knee-ankle length, m
  double scale = 1;          // leg_length / reference_leg
  StepShape shape;           // S (avatar, scaled) and H (user)
  double root_height = 0;    // standing root height above the floor, m
  double ankle_height[2] = {0, 0};  // ankle above the sole when standing, m
  Vec3 foot_offset[2];       // standing ankle target relative to the root (x, z), y unused
  Quat foot_rotation[2];     // standing model rotation of each ankle (heading 0)
};

// Throws legwork::Error if the skeleton lacks the leg roles (naming them).
// `upper_body` (optional, e.g. a frame of the avatar's own motion) gives the
// local rotations of the joints the legs do not drive (spine, arms, head);
// default: the rest pose with the upper arms hanging down.
WipModel make_wip_model(const Skeleton& avatar, const WipParams& params = {}, ConstPoseRef upper_body = {});

enum class StepKind : unsigned char { None, First, Consecutive };

// Everything one update produces (avatar-local unless said otherwise).
struct WipFrame {
  double time = 0;
  GaitPhase phase[2] = {GaitPhase::DoubleSupport, GaitPhase::DoubleSupport};
  unsigned events[2] = {0, 0};
  double h[2] = {0, 0}, v[2] = {0, 0};  // filtered height above floor, velocity
  double confidence[2] = {0, 0};
  double h1[2] = {0, 0};                 // height threshold in use
  double z_target[2] = {0, 0};           // equation output (depth, forward +)
  double z[2] = {0, 0};                  // smoothed IK-target depth
  double y[2] = {0, 0};                  // IK-target height, eq. 8 (avatar local)
  double root_offset = 0;                // vertical root offset, -dh while walking (eq. 6, 7)
  double speed = 0, distance = 0;        // forward speed m/s, distance walked m
  Vec3 root_position = Vec3::Zero();     // world
  Vec3 target_world[2] = {Vec3::Zero(), Vec3::Zero()};  // IK targets, world
  bool walking = false;
  int driver = -1;                       // foot driving the current step, -1 none
  StepKind kind = StepKind::None;
  double double_support_time = 0;        // both feet down, s
};

struct WipWorkspace {
  Pose pose;                       // the solved avatar pose after update()
  std::vector<Transform> model;    // its model-space transforms (legs up to the ankles)
  FootSignal feet[2];
  GaitMachine gait[2];
  StepSpeedEstimator step_speed;
  StepFrequencyEstimator frequency_speed;
  SpeedEstimator* custom_speed = nullptr;  // not owned; overrides the model's choice if set
  double heading = 0;              // yaw about +y, radians (0 = +z); the app may set it each frame
  // Mapping state.
  bool started = false, walking = false;
  int driver = -1;
  StepKind kind = StepKind::None;
  double last_time = 0, ds_time = 0, dh = 0, speed = 0, distance = 0;
  double z_target[2] = {0, 0}, z[2] = {0, 0};
  double gap[2] = {0, 0}, h_switch = 1;     // gap at mid-swing, faded out while descending
  double gap_up[2] = {0, 0}, h_off = 0;     // gap at foot-off, faded out while ascending
  Vec3 root_xz = Vec3::Zero();
  WipFrame frame;
};

WipWorkspace make_workspace(const WipModel& model);
void reset(const WipModel& model, WipWorkspace& ws);
// Fixes each foot's floor (the tracker-space ankle height when standing).
void set_floor(WipWorkspace& ws, double left, double right);
// One tracker sample -> one frame. Samples whose time does not increase are
// ignored (the previous frame is returned).
const WipFrame& update(const WipModel& model, const TrackerSample& sample, WipWorkspace& ws);

// ---- offline helpers -------------------------------------------------------

// Floor calibration from standing still: averages each ankle's height over
// the first `seconds`. Refuses (ok = false, message says why) if either
// ankle's height varies by more than `max_std` metres or too few samples are valid.
struct FloorCalibration {
  bool ok = false;
  double floor[2] = {0, 0};
  double spread[2] = {0, 0};  // std of the height, m
  std::string message;
};
FloorCalibration calibrate_floor(std::span<const TrackerSample> samples, double seconds = 3.0, double max_std = 0.03);

struct RunOptions {
  bool calibrate = true;            // calibrate the floor first (throws if not still)
  double calibration_seconds = 3.0;
  bool keep_poses = true;           // fill WipRun::motion
};
struct WipRun {
  std::vector<WipFrame> frames;
  Motion motion;  // the avatar at the samples' times (rate = params.signal.rate)
  FloorCalibration calibration;
};
WipRun run_wip(const WipModel& model, std::span<const TrackerSample> samples, const RunOptions& opt = {});

}  // namespace legwork::wip
