#pragma once
// Walking-in-place legs: tracked ankle heights -> gait phases -> IK-target
// depths and heights (the document's equations 1-8) -> a solved avatar pose
// that walks forward along the user's heading.
//
// The per-frame contract (docs/architecture.md):
//   const Model model = make_model(avatar_skeleton, settings);  // offline, may throw
//   State state(model);                                         // one per avatar
//   update(model, frame, state, pose.ref(), &info);             // every tracker frame
// update() reads the ankles (frame.foot(kLeft/kRight).position) and, when
// usable, the head's yaw as the walking heading; it never allocates, throws
// or does I/O. Offline helpers (tracker sources, floor calibration, whole-clip
// runs) are in legwork/wip/offline/.
#include <legwork/core/info_fields.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/ik/two_bone.hpp>
#include <legwork/wip/gait.hpp>
#include <legwork/wip/learned.hpp>
#include <legwork/wip/mapping.hpp>
#include <legwork/wip/speed.hpp>

#include <vector>

namespace legwork::wip {

enum class SpeedModel { StepSpeed, StepFrequency };
// Fore-aft IK-target depths: the document's equations 1-4 (the reference), or
// the table learned from real CMU walks (legwork/wip/learned.hpp; the model
// needs a LearnedMapping, see make_model).
enum class DepthMapping { Document, Learned };

struct MappingSettings {
  DepthMapping depth = DepthMapping::Document;
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
  double learned_smoothing_tau = 0;  // s: the same for the learned mapping (its table is continuous and already
                                     // lags with the filter; extra smoothing only delays: 0 = none)
  double body_tau = 0.05;       // s: same for the body's vertical offset
  double hint_forward = 0.29;   // m in front of the knee at the reference leg
  double knee_bend = 0.02;      // standing root lowered by this fraction of the leg (keeps knees soft)
  bool feet_flat = true;        // keep the ankle's standing model rotation
  SpeedModel speed_model = SpeedModel::StepSpeed;
  // Step-speed model gain (m/s of forward speed per m/s of mean vertical foot
  // speed); 0 = the gain calibrated for the chosen detector (step_speed_gain()).
  double speed_gain = 0;
  double stride_per_step = 0.65;  // step-frequency model, m per step
  double max_speed = 3.5;       // m/s cap
  double speed_tau = 0.3;       // s: smoothing of the forward speed
  double max_dt = 0.5;          // s: longer frame gaps are integrated as this (gaps over 5 s restart, FrameClock)
};

// The step-speed gains calibrated for each step detector (their phase timing
// differs, so the same stepping averages different foot speeds; docs/wip.md).
inline constexpr double kDocumentSpeedGain = 2.15;  // comfortable in-place stepping (0.15 m, 1.8 steps/s) -> ~1.3 m/s
// The adaptive detector's mid-swing and terminal events come at other points of the swing (the averaging
// windows hold less of the fast rise and fall): with 2.15 the shared CMU walks moved 0.28 m/s against
// their real 0.60; this gain matches the real speed pooled over the 57 walks (`wip eval`, walking speed).
inline constexpr double kAdaptiveSpeedGain = 4.61;

struct Settings {
  SignalSettings signal;    // rate = the tracker's nominal rate (used for the first frame's dt and the filter design)
  GaitSettings gait;
  MappingSettings mapping;
};

// The step-speed model's gain: mapping.speed_gain when set (> 0), else the
// chosen detector's calibrated gain.
double step_speed_gain(const Settings& settings);

// The avatar and everything derived from it. Built offline by make_model;
// immutable and shareable by any number of avatars on any threads.
class Model {
 public:
  struct Leg {
    ik::TwoBoneChain chain;
    double ankle_height = 0;              // ankle above the sole when standing, m
    Vec3 foot_offset = Vec3::Zero();      // standing ankle target relative to the root (x, z), y unused
    Quat foot_rotation = Quat::Identity();  // standing model rotation of the ankle (heading 0)
  };

  const Skeleton& skeleton() const { return skeleton_; }  // the output pose's skeleton
  const Settings& settings() const { return settings_; }
  double leg_length() const { return leg_length_; }  // measured hip-knee-ankle length, m
  double scale() const { return scale_; }            // leg_length / reference_leg
  const StepShape& shape() const { return shape_; }  // S (avatar, scaled) and H (user)
  double root_height() const { return root_height_; }  // standing root height above the floor, m
  const Pose& base_pose() const { return base_pose_; }  // standing pose the legs are solved from
  const Leg& leg(int side) const { return legs_[side & 1]; }
  // The learned depth table (a copy), or nullptr with the document's mapping.
  const LearnedMapping* learned() const { return has_learned_ ? &learned_ : nullptr; }

 private:
  friend Model make_model(const Skeleton& avatar, const Settings& settings, ConstPoseRef upper_body,
                          const LearnedMapping* learned);
  Model() = default;
  Skeleton skeleton_;
  Settings settings_;
  Leg legs_[2];
  Pose base_pose_;
  double leg_length_ = 0, scale_ = 1, root_height_ = 0;
  StepShape shape_;
  LearnedMapping learned_;
  bool has_learned_ = false;
};

// Throws legwork::Error if the skeleton lacks the leg roles (naming them) or
// the settings are unusable. `upper_body` (optional, e.g. a frame of the
// avatar's own motion) gives the local rotations of the joints the legs do
// not drive (spine, arms, head); default: the rest pose with the upper arms
// hanging down. `learned`: the table for settings.mapping.depth == Learned
// (copied; required then, ignored otherwise; legwork/wip/offline/learn.hpp
// builds and reads it).
Model make_model(const Skeleton& avatar, const Settings& settings = {}, ConstPoseRef upper_body = {},
                 const LearnedMapping* learned = nullptr);

enum class StepKind : unsigned char { None, First, Consecutive };

// Per-frame diagnostics (avatar-local unless said otherwise).
struct Info {
  double time = 0;
  GaitPhase phase[2] = {GaitPhase::DoubleSupport, GaitPhase::DoubleSupport};
  unsigned events[2] = {0, 0};
  double h[2] = {0, 0}, v[2] = {0, 0};  // filtered height above floor, velocity
  double confidence[2] = {0, 0};
  double h1[2] = {0, 0};                 // height threshold in use
  double z_target[2] = {0, 0};           // equation output (depth, forward +)
  double z[2] = {0, 0};                  // smoothed IK-target depth
  double y[2] = {0, 0};                  // IK-target height, eq. 8 (avatar local)
  double cycle[2] = {0, 0};              // cycle coordinate (learned.hpp): 0 rest, 0..1 rising, 1..2 descending
  double apex_estimate[2] = {0, 0};      // running estimate of the user's step apex, m
  int lead = -1;                         // foot that landed last (-1 none yet)
  double stride_period = 0;              // running mean of foot-off to foot-off of the same foot, s
  double since_strike = 0;               // s since the last foot strike (huge before the first)
  double root_offset = 0;                // vertical root offset, -dh while walking (eq. 6, 7)
  double speed = 0, distance = 0;        // forward speed m/s, distance walked m
  double heading = 0;                    // walking heading used, radians (0 = +z)
  double turn_rate = 0;                  // head yaw speed, rad/s, smoothed (the learned mapping's turning input)
  Vec3 root_position = Vec3::Zero();     // world
  Vec3 target_world[2] = {Vec3::Zero(), Vec3::Zero()};  // IK targets, world
  bool walking = false;
  int driver = -1;                       // foot driving the current step, -1 none
  StepKind kind = StepKind::None;
  double double_support_time = 0;        // both feet down, s
};

// What one avatar remembers between frames.
struct State {
  explicit State(const Model& model);

  FrameClock clock;
  std::vector<Transform> model_space;  // scratch: model-space transforms (sized once)
  FootSignal feet[2];
  GaitMachine gait[2];
  StepSpeedEstimator step_speed;
  StepFrequencyEstimator frequency_speed;
  double heading = 0;   // yaw about +y, radians (0 = +z): the head's last usable yaw
  bool heading_seen = false;  // a usable head was seen (turn_rate has a previous yaw)
  double heading_time = 0;    // time of that head sample, s
  double turn_rate = 0;       // |head yaw speed|, rad/s, smoothed over LearnedMapping::kTurnTau
  bool calibrated = false;            // set_floor was called: kept across restarts
  double calibrated_floor[2] = {0, 0};
  // Mapping.
  bool walking = false;
  int driver = -1;
  StepKind kind = StepKind::None;
  double ds_time = 0, dh = 0, speed = 0, distance = 0;
  double z_target[2] = {0, 0}, z[2] = {0, 0};
  double gap[2] = {0, 0}, h_switch = 1;     // gap at mid-swing, faded out while descending
  double gap_up[2] = {0, 0}, h_off = 0;     // gap at foot-off, faded out while ascending
  double cycle[2] = {0, 0};                 // cycle coordinates (learned mapping's input)
  int lead = -1;                            // foot that landed last
  double last_off[2] = {-1e9, -1e9};        // time of each foot's last foot-off
  double last_strike = -1e9;                // time of the last foot strike (either foot)
  double stride_period = LearnedMapping::kDefaultStridePeriod;  // s (learned mapping's cadence input)
  Vec3 root_xz = Vec3::Zero();
};

// Back to a fresh avatar (also forgets the floor calibration and the clock).
void reset(const Model& model, State& state);
// Fixes each foot's floor (the tracker-space ankle height when standing); a
// restart of the stream keeps it.
void set_floor(State& state, double left, double right);

// One tracker frame -> one pose on model.skeleton() (local rotations + root
// position). Time via state.clock: Rejected leaves state and `out` untouched;
// Restarted resets filters, gait and speed (keeping the floor calibration,
// the heading and the avatar's place) and consumes the frame. A foot that is
// not usable() is held (its confidence decays; a swinging foot is put down)
// and the frame is Degraded. An empty `out` (PoseRef{}) advances the state
// and fills `info` alike without solving the legs: for runs that need only
// the gait and the IK targets (the evaluation, the detector's tuning; about a
// quarter of the time, bench/wip_bench). Never allocates, throws or does I/O.
UpdateStatus update(const Model& model, const TrackerFrame& frame, State& state, PoseRef out, Info* info = nullptr);

// This frame's Info as named fields (InfoFields: the server's pose "info",
// the C API's lw_avatar_info_field); allocates nothing.
void describe(const Info& info, InfoFields& out);

}  // namespace legwork::wip
