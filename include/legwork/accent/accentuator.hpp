#pragma once
// Runtime: full-body pose synthesis from a headset and two hand controllers
// (CoolMoves 3.1.3-3.1.4), one Accentuator per avatar.
//
// Per update: the live input is featurised exactly like the database (hands
// relative to the head over the last kWindow samples at the database rate,
// interpolated from whatever rate the trackers run at), each hand's k nearest
// windows are found (distance threshold), every candidate pose is rotated
// about the vertical axis by the weighted closed-form alignment, the
// candidates are blended with weights inversely proportional to their match
// distance (left-arm joints from left-hand matches, right-arm joints from
// right-hand matches, every other joint from both), smoothed over time by the
// EWMA p_t = w p_t + (1 - w) p_{t-1} with w the global match weight
// (rotations on the sphere), limited to human joint ranges, scaled to the
// user's height and placed so its head sits at the headset.
//
// When no window matches within the threshold, or a device loses tracking
// (its last good head-relative position is held), the output converges over
// `fallback_seconds` to a direct mapping (neutral standing body facing the
// headset's heading, arms by two-bone IK to the real hands when legwork::ik is
// available) and back when matches return: never a frozen or exploding pose.
//
// Threading: the Database is shared read-only; each Accentuator owns its
// state (a few KB). update() allocates nothing and throws nothing.
#include <legwork/accent/database.hpp>
#include <legwork/accent/search.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace legwork::accent {

struct DeviceSample {
  Vec3 position = Vec3::Zero();      // world, metres
  Quat rotation = Quat::Identity();  // world (headset: identity looks along +z)
  bool valid = true;                 // false: tracking lost this sample
};

struct TrackerFrame {
  double time = 0;  // seconds, strictly increasing
  DeviceSample head, left, right;  // hands = wrists (a controller offset is the app's job)
};

struct AccentConfig {
  SearchMode search = SearchMode::Fast;
  float fast_eps = 5.0f;  // Fast mode: KD-tree pruning slack (squared-distance factor 1 + eps)
  int fast_max_checks = 1500;  // Fast mode: candidates examined per class tree (bounds p99)
  int k_left = 15, k_right = 15;  // matches per hand (at most kMaxK; the paper used 5, 15 measured better)
  // Match distance limit in units of Database::typical_distance(); <= 0: none.
  double threshold = 6.0;
  bool align = true;   // rotation alignment of candidates about y
  // Temporal smoothing: the paper's EWMA driven by the match weight, then a
  // critically damped spring on every local rotation (frame-rate independent,
  // continuous velocity, so candidate-set switches do not show as jerks).
  // false: neither (the ablation's "no smoothing").
  bool smooth = true;
  double smooth_halflife = 0.06;  // seconds the spring takes to halve an error; 0 = EWMA only (the paper)
  double min_smoothing_weight = 0.1;  // lower bound on w so the pose never freezes
  double user_height = 0;    // metres; 0 = the database skeleton's height
  double exaggeration = 1.0; // scales the input hands about the head before matching (and as hand IK targets)
  std::vector<std::string> classes;  // activity classes to match (empty = all)
  bool joint_limits = true;
  bool drive_head = true;    // head joint takes the headset's orientation
  double fallback_seconds = 0.4;  // time to converge to / from the direct mapping
  // 0..1: pull the synthesized arms onto the real hands (needs legwork::ik);
  // 1 = wrists on the controllers (the default for VR), 0 = the paper's pure synthesis.
  double hand_ik = 1.0;
  bool direct_only = false;  // skip matching: always the direct mapping (the IK baseline)
  // Reject candidates whose head tilt (angle of the head's up axis from
  // vertical) differs from the headset's by more than this (degrees; 0 = off):
  // keeps e.g. a lying swimmer's body off an upright user.
  double max_head_tilt_deg = 30.0;
};
// True when this build has legwork::ik (arms reach the real hands in the
// direct mapping and with hand_ik > 0); false: arms hang neutral there.
bool have_arm_ik();
inline constexpr int kMaxK = 32;

enum class FrameStatus : std::uint8_t {
  Matched,      // both hands matched
  Partial,      // one hand had no match within the threshold
  Unmatched,    // no match: converging to the direct mapping
  TrackingLost, // a device is invalid: its last good data is held
  Rejected,     // time did not increase or was not finite: output unchanged
};
const char* status_name(FrameStatus s);

struct FrameInfo {
  FrameStatus status = FrameStatus::Matched;
  double match_weight = 0;  // global match weight w_t (0..1)
  double fallback = 0;      // share of the direct mapping in the output (0..1)
  std::array<int, 2> matches{0, 0};
  std::array<float, 2> best_distance{0, 0};  // in typical-distance units
};

class Accentuator {
 public:
  // Throws legwork::Error for an unknown class or a database skeleton
  // without head/hands. The database must outlive the Accentuator.
  explicit Accentuator(const Database& db, AccentConfig cfg = {});

  FrameInfo update(const TrackerFrame& in);
  void reset();

  // The output pose on skeleton() (the database skeleton scaled to the user's
  // height): local rotations, root translation = world position (metres).
  ConstPoseRef pose() const { return out_.ref(); }
  const Skeleton& skeleton() const { return skel_; }
  const AccentConfig& config() const { return cfg_; }
  // The last matches per hand (window indices into the database).
  std::span<const Match> matches(int hand) const;
  // The live feature of the last update per hand (projected, as in the database).
  const Feature& live_feature(int hand) const { return live_[static_cast<std::size_t>(hand)]; }
  // Bytes of per-avatar state (workspace included).
  std::size_t state_bytes() const;

 private:
  struct Sample {
    double t = 0;
    Vec3 head = Vec3::Zero();
    std::array<Vec3, 2> hand{Vec3::Zero(), Vec3::Zero()};
  };
  struct Limit {
    Vec3 axis = Vec3::UnitY();
    double swing = 0, twist = 0;  // radians; 0 = unlimited
  };
  enum Group : std::uint8_t { Body, LeftArm, RightArm };

  void window_at(int hand, HandWindow& out) const;
  bool blend_candidates(double threshold);
  void make_direct_pose(const TrackerFrame& in);
  void finish_pose(const Quat& head_rotation, const Vec3& head_position, double ik_weight);
  void spring_filter(double dt);

  const Database* db_;
  AccentConfig cfg_;
  Skeleton skel_;
  double scale_ = 1;  // user height / database height
  std::vector<unsigned char> class_mask_;
  std::vector<Group> group_;
  std::vector<Limit> limit_;
  Pose neutral_;

  // Ring buffer of recent input samples.
  static constexpr int kRing = 128;
  std::array<Sample, kRing> ring_{};
  int ring_head_ = -1, ring_size_ = 0;
  std::array<Vec3, 2> hand_offset_{};  // last good head-relative hand positions
  Vec3 last_head_ = Vec3::Zero();
  Quat last_head_rot_ = Quat::Identity();
  bool have_head_ = false, started_ = false;
  double last_time_ = 0;
  double fallback_ = 0.0;  // share of the direct mapping

  // Workspace.
  std::array<std::array<Match, kMaxK>, 2> matches_{};
  std::array<int, 2> match_count_{0, 0};
  std::array<Feature, 2> live_{};
  std::array<std::array<Quat, kMaxK>, 2> root_aligned_{};
  std::array<std::array<double, kMaxK>, 2> weight_{}, confidence_{};
  std::array<std::array<const float*, kMaxK>, 2> pose_rot_{};  // each candidate's pose rotations
  std::vector<Quat> model_rot_;
  Pose synth_, smoothed_, direct_, out_;
  std::vector<Transform> model_;
  double match_weight_ = 0;
  bool have_smoothed_ = false;
  // Spring filter state: filtered local rotations and their angular velocities.
  std::vector<Quat> spring_rot_;
  std::vector<Vec3> spring_vel_;
  bool have_spring_ = false;
};

// Helpers for BVH-driven sessions and evaluations (allocate).
// Devices from a motion: head = Head joint (position, model rotation), hands =
// wrist joints, time = frame / fps. Throws if roles are missing.
std::vector<TrackerFrame> tracker_frames_from_motion(const Motion& m);

struct AccentRun {
  Motion output;                 // one frame per input frame, on Accentuator::skeleton()
  std::vector<FrameInfo> info;   // per frame
  double seconds = 0;            // time spent in update() only
};
// Runs one Accentuator over the frames (output labelled at `fps`).
AccentRun accentuate(const Database& db, const AccentConfig& cfg, std::span<const TrackerFrame> frames, double fps);
// Convenience: input = a motion's head and hands, resampled to the database
// rate; user_height (if 0) = the motion's standing height.
AccentRun accentuate_motion(const Database& db, AccentConfig cfg, const Motion& input);

}  // namespace legwork::accent
