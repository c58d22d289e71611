#pragma once
// Pose-reconstruction metrics for head-and-hands avatar methods.
// Everything is measured on the role joints (skeleton roles: pelvis, spine,
// chest, neck, head, clavicles, shoulders, elbows, hands, hips, knees, ankles,
// toes), so an output on one skeleton can be scored against ground truth on
// another. Positions are model space, metres; reported errors are centimetres.
// Offline code: may allocate; never throws on finite input, and NaN-free input
// gives NaN-free output (an undefined figure, e.g. the correlation of a
// constant series, is left out of its average, and reported as NaN only when
// nothing is left).
#include <legwork/core/motion.hpp>

#include <array>
#include <span>
#include <string_view>
#include <vector>

namespace legwork::eval {

// Body-part groups of the document's Figure 4 A.
enum class Part : int { LeftHand = 0, RightHand, UpperBody, LowerBody, FullBody, Count };
constexpr int kPartCount = static_cast<int>(Part::Count);
// "left_hand", "right_hand", "upper_body", "lower_body", "full_body".
std::string_view part_name(Part p);
// Upper body = head, neck, arms and torso (spine, chest, clavicles); lower
// body = pelvis, legs and feet; hands are the wrist joints; full body = all
// role joints.
bool role_in_part(Role r, Part p);

// Role-joint positions over time: frames x kRoleCount, frame-major.
struct RoleTrack {
  double fps = 90.0;
  int frames = 0;
  std::array<bool, kRoleCount> present{};  // role resolved on the source skeleton
  std::vector<Vec3> positions;             // model space, metres (zero where absent)

  const Vec3& at(int f, Role r) const {
    return positions[static_cast<std::size_t>(f) * kRoleCount + static_cast<std::size_t>(r)];
  }
  Vec3& at(int f, Role r) {
    return positions[static_cast<std::size_t>(f) * kRoleCount + static_cast<std::size_t>(r)];
  }
  bool has(Role r) const { return present[static_cast<std::size_t>(r)]; }
};
// Forward kinematics of every frame, keeping the role joints.
RoleTrack role_track(const Motion& m);
// An empty track of `frames` frames with the given roles present.
RoleTrack make_track(double fps, int frames, const std::array<bool, kRoleCount>& present);


struct MetricOptions {
  // Foot contact: a foot joint is in contact while it is within this height
  // above its own floor level (5th percentile of its height over the trial).
  double contact_height = 0.03;  // metres
};

// Metrics of one output track against its ground truth (same length and rate).
struct TrialMetrics {
  int frames = 0;
  std::array<double, kPartCount> part_cm{};  // mean per-joint Euclidean error, cm
  double mpjpe_cm = 0;                       // = part_cm[FullBody]
  double mpjve_cm_s = 0;    // mean per-joint velocity error (central differences), cm/s
  double jitter = 0;        // output's mean jerk magnitude over role joints, 10^2 m/s^3
  double jitter_truth = 0;  // the same for the ground truth (the capture's own jitter)
  // Pearson correlation between input (= ground-truth) and output hand
  // positions, each relative to the input head, per axis x, y, z; and the
  // mean over the axes. [0] = left hand, [1] = right hand.
  std::array<std::array<double, 3>, 2> hand_correlation_axis{};
  std::array<double, 2> hand_correlation{};
  // Mean horizontal slide of a foot joint (ankles and toes) per frame while it
  // stays in contact over two consecutive frames, cm per frame at the track
  // rate; the ground truth's figure shows the capture's own slide.
  double foot_skating_cm = 0;
  double foot_skating_truth_cm = 0;
  double foot_contact_fraction = 0;  // of output foot-joint frames in contact
};
// Throws legwork::Error if the tracks differ in length or rate, or share no
// role joint.
TrialMetrics evaluate_trial(const RoleTrack& output, const RoleTrack& truth, const MetricOptions& opt = {});

// Mean jerk magnitude (third central difference x fps^3) over the present
// role joints and all frames, m/s^3. 0 with fewer than 4 frames.
double mean_jerk(const RoleTrack& t);
// Mean per-frame horizontal slide of the foot joints in contact (metres) and
// the fraction of foot-joint frames in contact.
struct FootSkate {
  double slide_m = 0;
  double contact_fraction = 0;
};
FootSkate foot_skating(const RoleTrack& t, double contact_height);

// Frame-weighted mean of several trials' metrics (a fold's several held-out
// trials). Correlations average over the trials where they are defined.
TrialMetrics combine(std::span<const TrialMetrics> trials);

}  // namespace legwork::eval
