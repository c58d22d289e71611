#pragma once
// Runtime: full-body pose synthesis from a headset and two hand controllers
// (CoolMoves 3.1.3-3.1.4), on the per-frame contract of docs/architecture.md:
// an immutable accent::Model (database + settings + everything derived from
// them: the skeleton scaled to the user, class mask, joint groups and limits,
// the neutral pose) shared by any number of avatars, one accent::State per
// avatar, and accent::update().
//
// Per update: the live input is featurised exactly like the database (hands
// relative to the head at kWindow samples kStride apart at the database rate,
// 178 ms, interpolated from whatever rate the trackers run at), each hand's k nearest
// windows are found (distance threshold), every candidate pose is rotated
// about the vertical axis by the weighted closed-form alignment, the
// candidates are blended with weights inversely proportional to their match
// distance (left-arm joints from left-hand matches, right-arm joints from
// right-hand matches, every other joint from both), smoothed over time by the
// EWMA p_t = w p_t + (1 - w) p_{t-1} with w the global match weight
// (rotations on the sphere) and a critically damped spring, limited to human
// joint ranges, scaled to the user's height and placed so its head sits at
// the headset; hand IK then pulls the wrists onto the controllers.
//
// When no window matches within the threshold, or a device loses tracking
// (its last good head-relative position is held), the output converges over
// `fallback_seconds` to a direct mapping (neutral standing body facing the
// headset's heading, arms by two-bone IK to the real hands) and back when
// matches return: never a frozen or exploding pose.
//
// Threading: the Database and the Model are shared read-only; each State is
// one avatar's (a few KB). update() allocates nothing and throws nothing.
#include <legwork/accent/database.hpp>
#include <legwork/accent/search.hpp>
#include <legwork/core/info_fields.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/ik/full_body.hpp>
#include <legwork/ik/two_bone.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace legwork::accent {

inline constexpr int kMaxK = 32;
// Horizontal foot speed (m/s, scaled with the user) that separates a swing from
// a stand: Settings::foot_swing_speed's default, and the speed below which a
// foot pushed into the floor is planted (Settings::floor; at any speed while
// the user is bent over or lying, or when it is pushed more than 5 cm in).
inline constexpr double kDefaultSwingSpeed = 0.5;

struct Settings {
  SearchMode search = SearchMode::Fast;
  // Fast mode: KD-tree pruning slack (squared-distance factor 1 + eps). 2
  // (was 5): recall@15 0.83 -> 0.96 on a held-out boxing trial's class
  // database at the same CPU time per frame (docs/accent.md).
  float fast_eps = 2.0f;
  int fast_max_checks = 1500;  // Fast mode: candidates examined per class tree (bounds p99)
  // Seconds between two searches of the database (0 = every frame, the
  // document's). In between, as motion matching does, each hand's matches
  // are continued instead: the last frame's matches and each one's next
  // window in its trial (same speed, one hop on) are ranked by their distance
  // to this frame's query, with no index search; class recognition waits for
  // the next search. A search also runs when a hand had no match. 0.044: one
  // window hop of the default build (4 samples at 90 Hz), so the continued
  // windows reach the next search's; at 90 Hz every 4th frame searches
  // (docs/accent.md, "Searching every hop").
  double search_interval = 0.044;
  int k_left = 15, k_right = 15;  // matches per hand (at most kMaxK; the paper used 5, 15 measured better)
  // Match distance limit in units of Database::typical_distance(); <= 0: none.
  double threshold = 6.0;
  bool align = true;   // rotation alignment of candidates about y
  // Temporal smoothing: the paper's EWMA driven by the match weight, then a
  // critically damped spring on every local rotation (frame-rate independent,
  // continuous velocity, so candidate-set switches do not show as jerks).
  // false: neither (the ablation's "no smoothing").
  bool smooth = true;
  double smooth_halflife = 0.08;  // seconds the spring takes to halve an error (0.06 before the swing clearance); 0 = EWMA only (the paper)
  double min_smoothing_weight = 0.1;  // lower bound on w so the pose never freezes
  // Share (0..1) of the matched candidates' own motion played forward in the
  // smoothing: the EWMA and the spring filter advance their pose by the
  // blended candidates' joint velocities (each candidate's pose one database
  // frame ahead in its trial) before they pull toward this frame's blend, so
  // a steadily moving body no longer lags behind its target. 0 = the filters
  // pull toward a still target (before).
  double smooth_feedforward = 1.0;
  // Times (1..20) the spring's half-life on the root rotation for a lying user
  // (head at most 0.5 of their height up; from 1 at 0.8 and above): a lying
  // body turns slowly, and each wobble of its root swings the feet, a body's
  // length away from the head, across the floor. 8: tried 4 and 8 on the
  // evaluation (docs/accent.md, "A lying user's root smoothed longer").
  // 1 = off (the root smoothed like every joint).
  double lying_root_smoothing = 8.0;
  // Share (0..1) of a lying user's candidate turn taken from the headset, in
  // place of the hands' alignment: the yaw that points the candidate's crown
  // (the head's up axis, horizontally: lying on the front or the back, the
  // top of the head points away from the feet) where the headset's points,
  // then the roll about it that faces the candidate's face where the
  // headset's faces (a front stroke laid on its back); and of the IK body
  // (which stands) taken out, its share going to the direct mapping laid
  // flat along the headset's crown (also the body shown where the hands find
  // no match, in place of the standing pose). All as the head goes from 0.8
  // of the user's height down to 0.5. Without it a back stroke matched
  // against front strokes was turned end over end, or stood up by the IK
  // blend or the direct mapping (docs/accent.md, "A lying body turned by its
  // crown" and "A lying user's fallback lies flat"). 0 = off.
  double lying_crown = 1.0;
  double user_height = 0;    // metres; 0 = the database skeleton's height
  double exaggeration = 1.0; // scales the input hands about the head before matching (and as hand IK targets)
  std::vector<std::string> classes;  // activity classes to match (empty = all)
  // "No class given": when the session allows more than one class (classes
  // empty = every class of the database), recognise the activity from the
  // input and search only that class's index. Per allowed class a match cost
  // (the mean over the hands of the nearest window's distance in that class,
  // head-tilt gate applied, in typical distances) is smoothed over
  // class_seconds; the active class's cost comes from the frame's own search,
  // another class is probed (round robin) every class_seconds / (2 x the
  // other classes), so each is scored about twice per class_seconds. The active class
  // changes only when another's smoothed cost is lower by the fraction
  // class_margin for class_hold_seconds (hysteresis). false: every allowed
  // class is searched every frame (their class trees, one shared check budget).
  bool recognize_class = true;
  // Other classes at a cost, while recognising the class: the frame's search
  // also covers the allowed classes other than the recognised one, their
  // distances multiplied by this factor (>= 1; 1 = no preference), so a
  // user whose motion the recognised class's trials do not cover can still
  // take a nearer window of another class (docs/accent.md, "Other classes at
  // a cost"). 0 = only the recognised class is searched.
  double other_class_cost = 1.25;
  double class_seconds = 0.5;
  double class_margin = 0.1;
  double class_hold_seconds = 0.5;
  bool joint_limits = true;
  bool drive_head = true;    // head joint takes the headset's orientation
  double fallback_seconds = 0.4;  // time to converge to / from the direct mapping
  // 0..1: pull the synthesized arms onto the real hands by two-bone IK;
  // 1 = wrists on the controllers (the default for VR), 0 = the paper's pure synthesis.
  double hand_ik = 1.0;
  bool direct_only = false;  // skip matching: always the direct mapping (ablation only; the IK baseline is ik::)
  // Reject candidates whose head tilt (angle of the head's up axis from
  // vertical) differs from the headset's by more than this (degrees; 0 = off):
  // keeps e.g. a lying swimmer's body off an upright user.
  double max_head_tilt_deg = 30.0;
  // Head-height gate, share of body height (head height over standing height,
  // the stored Travel[3]; 0 = off). While the user stands upright (head at
  // least 0.8 of their height up), reject candidates whose head is lower than
  // the user's by more than this: keeps a swimmer lying on a bench, whose head
  // may be as upright as a standing user's, off a standing user (with no
  // candidate left the engine falls back to the IK body). While the user is
  // lower, reject those whose head is higher by more than this, unless that
  // would leave none: keeps a kneeling or standing body off a lying user.
  // docs/accent.md, "Head-height gate".
  double max_head_height_diff = 0.15;
  // Foot locking: the database's per-pose foot contacts, blended over the
  // matched candidates with their weights, say whether a foot is planted (on
  // above contact_on, off below contact_off). A planted foot keeps its world
  // position and orientation while the leg follows by two-bone IK; when the
  // contact ends the foot blends back to the synthesized pose over
  // foot_release_seconds. A planted foot the leg cannot reach is pulled along
  // the leg (mostly up, like a heel rising); with foot_lock_follow_seconds > 0
  // it also creeps toward the synthesized foot with that time constant, once
  // it has been planted for foot_lock_hold_seconds (0.2 s, the median true
  // stance of the shared running trials: a quick step's foot never creeps;
  // 0 = it creeps from touch-down).
  bool foot_lock = true;
  double foot_lock_follow_seconds = 0.15;
  double foot_lock_hold_seconds = 0.2;
  double contact_on = 0.6, contact_off = 0.4;
  double foot_release_seconds = 0.15;
  // A released foot (contact ended) travels back to the synthesized foot
  // lifted by up to foot_lift_height (metres, a sin^2 arc over the release),
  // instead of sliding along the floor; 0 = no lift.
  double foot_lift_height = 0.05;
  // A planted foot stays exactly where it touched down while the synthesized
  // foot is within foot_lock_slack (metres, scaled with the user) of it; only
  // the distance beyond creeps (foot_lock_follow_seconds). 0 = all of it
  // creeps (the default: 0.1 m cut skating 2.97x -> 2.54x but cost 0.2-0.3 cm
  // of lower-body error, docs/accent.md).
  double foot_lock_slack = 0.0;
  // Swing clearance: a free foot whose synthesized ankle moves horizontally
  // faster than foot_swing_speed (m/s, scaled with the user) is swinging and is
  // lifted (smoothly) until its ankle and its toe each pass at least
  // foot_lift_height above their floors (the lowest height each recently had)
  // instead of grazing it: the blend of candidates in different phases of a
  // step flattens the swing. Not while the headset is tilted 60-80 degrees or
  // more (a swimmer). 0 = off.
  double foot_swing_speed = kDefaultSwingSpeed;
  // The floor: the play area's floor is the plane y = floor_height (metres; 0
  // for a floor-level tracking origin, as the IK body's). With floor on, a
  // foot is never shown through it (the ankle and the toe stay at least their
  // rest heights above it; the knee bends), a foot the synthesized pose pushes
  // into it is planted (with foot_lock) while moving slower than
  // kDefaultSwingSpeed, at any speed while the user is bent over or lying
  // (the headset tilted past 60 degrees, where the swing clearance does not
  // lift it in full; fixed, so foot_swing_speed = 0 leaves planting on), and
  // at any speed when its ankle is pushed more than 5 cm (scaled) into it (the
  // body coming down onto its feet: a landing, a crouch), and
  // swinging feet clear it by foot_lift_height. Off, feet
  // follow the synthesized pose below the floor too (a body lowered to a
  // swimmer's headset on a bench put them up to 60 cm under it).
  bool floor = true;
  double floor_height = 0.0;
  // Confidence blend toward the full-body IK body (legwork::ik on the same
  // skeleton, run beside the synthesis): share of the IK pose in the output =
  // ik_blend_min, rising smoothly to ik_blend_max as the match distance
  // (best distance of the two hands, in typical distances, smoothed over
  // ik_blend_seconds) goes from ik_blend_near to ik_blend_far, i.e. where the
  // database does not cover the user; none of it while the headset is tilted
  // more than 80 degrees from upright (fading from 60) (the IK body stands);
  // a lying user's share goes to the direct mapping laid flat (lying_crown). 0 / 0 = off.
  double ik_blend_min = 0.1, ik_blend_max = 1.0;
  double ik_blend_near = 1.5, ik_blend_far = 3.0;
  double ik_blend_seconds = 0.5;
  // The user's travel in the match: each hand's search retrieves 1.5 times its
  // usual candidates by hand features, then keeps the k with the lowest
  // hand distance / typical distance + travel_weight x travel distance, where
  // the travel distance compares the headset's travel (horizontal speed over
  // 0.2 and 0.6 s, vertical velocity, height over body height; database.hpp,
  // Travel) with the candidate's, each term in units of its spread over the
  // database. Walking, running and jumping users get legs that travel. 0 =
  // off (hand features only).
  double travel_weight = 2.0;
};

// How the frame's pose was made (Info::match).
enum class MatchStatus : std::uint8_t {
  Matched,      // both hands matched
  Partial,      // one hand had no match within the threshold
  Unmatched,    // no match: converging to the direct mapping
  TrackingLost, // a device is unusable: its last good data is held
  Rejected,     // the frame was rejected (time): nothing changed
};
const char* status_name(MatchStatus s);

struct Info {
  MatchStatus match = MatchStatus::Matched;
  double match_weight = 0;  // global match weight w_t (0..1)
  double fallback = 0;      // share of the direct mapping in the output (0..1)
  std::array<int, 2> matches{0, 0};
  std::array<float, 2> best_distance{0, 0};  // in typical-distance units
  std::array<float, 2> contact{0, 0};        // blended foot contact of the candidates (left, right), 0..1
  std::array<bool, 2> foot_locked{false, false};
  double ik_share = 0;  // share of the IK body in the output (0..1)
  // Settings::recognize_class: the recognised class (index into
  // Database::classes(); -1 = not recognising, all allowed classes searched).
  int active_class = -1;
  // How many classes this frame's search covered: every allowed one when not
  // recognising; while recognising, the recognised class plus the others
  // searched at other_class_cost (those whose probed cost could still enter
  // the matches).
  int classes_searched = 0;
  // Settings::search_interval: whether this frame searched the database
  // (false: the last matches were continued in their trials).
  bool searched = true;
};

// Everything derived from the database and the settings; immutable.
class Model {
 public:
  enum Group : std::uint8_t { Body, LeftArm, RightArm };
  struct Limit {
    Vec3 axis = Vec3::UnitY();
    double swing = 0, twist = 0;  // radians; 0 = unlimited
    double cos_half_swing = 1, cos_half_twist = 1;  // cos(swing / 2), cos(twist / 2): within the limit without an acos
  };

  const Database& database() const { return *db_; }
  const Settings& settings() const { return settings_; }
  // The output skeleton: the database skeleton scaled to the user's height.
  const Skeleton& skeleton() const { return skeleton_; }
  double scale() const { return scale_; }  // user height / database height
  std::span<const unsigned char> class_mask() const { return class_mask_; }
  // The classes the session allows (indices into Database::classes()), and
  // whether the engine recognises one of them (Settings::recognize_class and
  // more than one allowed).
  std::span<const int> allowed_classes() const { return allowed_; }
  bool recognizes_class() const { return recognizes_; }
  Group group(int joint) const { return group_[static_cast<std::size_t>(joint)]; }
  const Limit& limit(int joint) const { return limit_[static_cast<std::size_t>(joint)]; }
  const Pose& neutral() const { return neutral_; }
  // Leg chains (0 left, 1 right) and their lengths (thigh + shin, metres);
  // can_lock_feet() is false when the skeleton lacks hip, knee or ankle roles.
  const ik::TwoBoneChain& leg(int foot) const { return leg_[static_cast<std::size_t>(foot)]; }
  double leg_length(int foot) const { return leg_length_[static_cast<std::size_t>(foot)]; }
  int toe(int foot) const { return toe_[static_cast<std::size_t>(foot)]; }  // -1: no toe below the ankle
  // Rest heights (metres) of the ankle and the toe above the foot's sole (its
  // lowest joint or end site): how high each stays above the floor.
  double ankle_rest_height(int foot) const { return ankle_rest_[static_cast<std::size_t>(foot)]; }
  double toe_rest_height(int foot) const { return toe_rest_[static_cast<std::size_t>(foot)]; }
  bool can_lock_feet() const { return can_lock_feet_; }
  // Arm chains (0 left, 1 right), their lengths (upper arm + forearm, metres)
  // and clavicles (-1 when the skeleton has none): hand IK's reach.
  const ik::TwoBoneChain& arm(int hand) const { return arm_[static_cast<std::size_t>(hand)]; }
  double arm_length(int hand) const { return arm_length_[static_cast<std::size_t>(hand)]; }
  int clavicle(int hand) const { return clavicle_[static_cast<std::size_t>(hand)]; }
  // The full-body IK model on skeleton() (null when that skeleton cannot take
  // one, or the IK blend is off).
  const ik::Model* ik_model() const { return ik_.get(); }
  // The pose one hop later in the same trial (-1 at a trial's last window).
  int next_pose(int pose) const { return next_pose_[static_cast<std::size_t>(pose)]; }
  // The window that continues window w in its trial: the same speed and copy
  // at the next pose (one hop on); -1 at the trial's end (Settings::search_interval).
  int next_window(int w) const;
  // Model bytes (shared by every avatar of this model).
  std::size_t bytes() const;

 private:
  friend Model make_model(const Database&, const Settings&);
  const Database* db_ = nullptr;
  Settings settings_;
  Skeleton skeleton_;
  double scale_ = 1;
  std::vector<unsigned char> class_mask_;
  std::vector<int> allowed_;
  bool recognizes_ = false;
  std::vector<Group> group_;
  std::vector<Limit> limit_;
  std::vector<int> next_pose_;
  Pose neutral_;
  std::array<ik::TwoBoneChain, 2> leg_{};
  std::array<double, 2> leg_length_{0, 0};
  std::array<int, 2> toe_{-1, -1};
  std::array<double, 2> ankle_rest_{0, 0}, toe_rest_{0, 0};
  bool can_lock_feet_ = false;
  std::array<ik::TwoBoneChain, 2> arm_{};
  std::array<double, 2> arm_length_{0, 0};
  std::array<int, 2> clavicle_{-1, -1};
  std::shared_ptr<const ik::Model> ik_;
};

// Throws legwork::Error for an unknown class (listing the database's), k out
// of range, a non-positive exaggeration or height, or a database skeleton
// without head/hands/pelvis. The database must outlive the model.
Model make_model(const Database& db, const Settings& settings = {});

// One avatar's memory between frames, and its scratch space.
struct State {
  explicit State(const Model& model);
  // Bytes of per-avatar state (workspace included).
  std::size_t bytes() const;

  struct Sample {
    double t = 0;
    Vec3 head = Vec3::Zero();
    std::array<Vec3, 2> hand{Vec3::Zero(), Vec3::Zero()};
  };
  FrameClock clock;
  // Ring buffer of recent input samples.
  static constexpr int kRing = 128;
  std::array<Sample, kRing> ring{};
  int ring_head = -1, ring_size = 0;
  std::array<Vec3, 2> hand_offset{};  // last good head-relative hand positions
  Vec3 last_head = Vec3::Zero();
  Quat last_head_rot = Quat::Identity();
  bool have_head = false;
  double fallback = 0.0;  // share of the direct mapping
  double match_weight = 0;
  bool have_smoothed = false, have_spring = false;
  // The last matches per hand (window indices into the database) and live features.
  std::array<std::array<Match, kMaxK>, 2> matches{};
  std::array<int, 2> match_count{0, 0};
  std::array<Feature, 2> live{};
  Travel travel{};  // the user's head travel this frame (database space; Settings::travel_weight)
  // Foot locking (Settings::foot_lock), per foot (0 left, 1 right).
  struct FootLock {
    bool locked = false;
    double weight = 0;      // share of the lock in the output (1 while locked, fading after)
    Vec3 position = Vec3::Zero();      // world position of the planted ankle
    Quat rotation = Quat::Identity();  // world rotation of the planted ankle
    double held = 0;                   // seconds since touch-down
    // Swing clearance (Settings::foot_swing_speed).
    bool have_floor = false;
    double floor = 0;                  // lowest recent synthesized ankle height (relaxing upward; not below the floor)
    double toe_floor = 0;              // lowest recent height of the toe (ball of the foot) as shown
    Vec3 previous = Vec3::Zero();      // last frame's synthesized ankle
    double swing = 0;                  // 0..1: the foot is swinging
    double lift = 0, lift_velocity = 0;  // the clearance's lift (spring-smoothed), metres and m/s
  };
  std::array<FootLock, 2> foot{};
  std::array<double, 2> contact{0, 0};  // this frame's blended candidate contact
  // The IK body (Settings::ik_blend_*): its avatar, pose and blend state.
  std::optional<ik::State> ik;
  Pose ik_pose;
  double ik_distance = 0;  // smoothed match distance, typical distances
  bool have_ik_distance = false;
  double ik_share = 0;
  double laid_share = 0;  // share of the flat-laid direct mapping (a lying user's low-confidence body)
  // Class recognition (Settings::recognize_class), per database class.
  int active_class = -1;            // -1: not chosen yet
  int challenger = -1;              // the class currently beating it by the margin...
  double challenger_seconds = 0;    // ...for this long
  int probe_next = 0;               // index into Model::allowed_classes() of the next class probed
  double next_probe = 0;            // input time of the next probe
  int class_switches = 0;           // since the last reset
  std::vector<double> class_cost;   // smoothed match cost, typical distances (< 0: unknown)
  std::vector<double> class_time;   // input time of each class's last cost update
  std::vector<std::array<int, 2>> class_seed;  // best window per class and hand (seeds the probes)
  std::vector<unsigned char> active_mask, probe_mask;
  std::vector<float> active_scale;  // Settings::other_class_cost around the recognised class
  // Settings::search_interval: input seconds since the last search (a frame
  // after a reset searches anyway: it has no matches) and this frame's choice.
  double since_search = 0;
  bool search_now = true;
  Pose smoothed;                // EWMA output
  std::vector<Quat> spring_rot; // spring filter: filtered local rotations...
  std::vector<Vec3> spring_vel; // ...and their angular velocities
  std::vector<Vec3> motion_vel; // the blended candidates' joint angular velocities (rad/s; smooth_feedforward)
  // Scratch (no meaning between frames).
  std::array<Match, 2 * kMaxK> candidates{};  // the travel re-rank's candidates
  std::array<float, 2 * kMaxK> candidate_cost{};
  std::array<std::array<Quat, kMaxK>, 2> root_aligned{};
  std::array<std::array<Quat, kMaxK>, 2> root_next_aligned{};
  std::array<std::array<const float*, kMaxK>, 2> next_rot{};  // each candidate's next pose (its own at a trial's end)
  std::array<std::array<double, kMaxK>, 2> ahead{};  // share of the way to the next pose one database frame on
  std::array<std::array<double, kMaxK>, 2> weight{}, confidence{};
  std::array<std::array<const float*, kMaxK>, 2> pose_rot{};  // each candidate's pose rotations
  // The candidate blend's scratch (blend_matches): per joint, each hand's share (2 x n), and the
  // reference hemisphere and the two sums (4 floats a joint each).
  std::vector<float> blend_share, blend_ref, blend_sum, blend_sum_ahead;
  std::vector<Quat> model_rot;
  std::vector<Transform> model_space;
  Pose synth, direct;
};

void reset(const Model& model, State& state);

// One frame: head and hands of `frame` in, the pose on model.skeleton() out
// (local rotations; root translation = world position, metres). `out` must
// have the skeleton's joint count (else Rejected). Rejected frames leave
// state and `out` untouched.
UpdateStatus update(const Model& model, const TrackerFrame& frame, State& state, PoseRef out, Info* info = nullptr);

// This frame's Info as named fields (InfoFields: the server's pose "info",
// the C API's lw_avatar_info_field); allocates nothing.
void describe(const Info& info, InfoFields& out);

// The last matches of one hand (0 left, 1 right).
std::span<const Match> last_matches(const State& state, int hand);

}  // namespace legwork::accent
