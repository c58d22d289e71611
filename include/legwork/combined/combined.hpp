#pragma once
// One avatar, two sources (runtime): the upper body from the headset and the
// two controllers (accentuation over a database, or the full-body IK avatar
// without one) and the legs from walking-in-place on the ankle or foot
// trackers, on one skeleton. The leg joints (hips down) fade between the two
// over `blend_time` when the feet are found or lost, so the legs never pop;
// the pelvis and everything above it is the upper-body method's. Where the
// avatar walks to is the application's: Info gives walking-in-place's speed,
// heading and distance.
//
//   const combined::Model model = combined::make_model(db, settings);   // offline, may throw
//   combined::State state(model);                                        // per avatar
//   Pose pose(model.skeleton());
//   combined::update(model, frame, state, pose.ref(), &info);           // every frame
#include <legwork/accent/accent.hpp>
#include <legwork/core/info_fields.hpp>
#include <legwork/core/motion.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/ik/full_body.hpp>
#include <legwork/ik/two_bone.hpp>
#include <legwork/wip/wip.hpp>

#include <array>
#include <optional>
#include <vector>

namespace legwork::combined {

struct Settings {
  double blend_time = 0.3;  // s for the legs to fade fully between the two sources (> 0)
  // Foot locking: while walking-in-place has a foot down, that ankle is held
  // where it touched down (two-bone IK on the leg) as the root travels with the
  // head; released over unlock_time when the foot lifts or when the leg can no
  // longer reach it (then held again where it is once the release has faded).
  bool foot_lock = true;
  double unlock_time = 0.1;  // s (> 0)
  accent::Settings accent;  // the upper body with a database
  ik::Settings ik;          // the upper body without one
  wip::Settings wip;        // the legs
};

class Model {
 public:
  // The output skeleton (the upper-body method's; the legs run on the same).
  const Skeleton& skeleton() const { return accent_ ? accent_->skeleton() : ik_->skeleton(); }
  const Settings& settings() const { return settings_; }
  bool accentuated() const { return accent_.has_value(); }
  const accent::Model* accent() const { return accent_ ? &*accent_ : nullptr; }
  const ik::Model* ik() const { return ik_ ? &*ik_ : nullptr; }
  const wip::Model& wip() const { return *wip_; }
  // Joints driven by the legs source: every joint below a hip, hips included.
  const std::vector<int>& leg_joints() const { return leg_joints_; }
  const ik::TwoBoneChain& leg(int foot) const { return legs_[static_cast<std::size_t>(foot)]; }

 private:
  friend Model make_model(const accent::Database&, const Settings&, const wip::LearnedMapping*);
  friend Model make_model(const Skeleton&, const Settings&, const wip::LearnedMapping*);
  void finish(const wip::LearnedMapping* learned);
  Settings settings_;
  std::optional<accent::Model> accent_;
  std::optional<ik::Model> ik_;
  std::optional<wip::Model> wip_;
  std::vector<int> leg_joints_;
  std::array<ik::TwoBoneChain, 2> legs_{};
};

// Upper body by accentuation over `db` (which must outlive the model), at
// settings.accent.user_height. Throws legwork::Error (from either method, or
// for blend_time <= 0 or a skeleton without hips). `learned`: the legs' table
// when settings.wip.mapping.depth == Learned (copied; see wip::make_model).
Model make_model(const accent::Database& db, const Settings& settings = {}, const wip::LearnedMapping* learned = nullptr);
// Upper body by the full-body IK avatar on `skeleton`.
Model make_model(const Skeleton& skeleton, const Settings& settings = {}, const wip::LearnedMapping* learned = nullptr);

struct State {
  explicit State(const Model& model);
  FrameClock clock;
  std::optional<accent::State> accent;
  std::optional<ik::State> ik;
  wip::State wip;
  double legs_weight = 0;  // 0 = the upper method's own legs, 1 = walking-in-place's
  std::array<bool, 2> locked{false, false};    // foot held where it touched down
  std::array<bool, 2> released{false, false};  // let go (out of reach) until the release has faded
  std::array<Vec3, 2> lock_at{Vec3::Zero(), Vec3::Zero()};  // world position of the held ankle
  std::array<double, 2> lock_weight{0, 0};                  // 0..1 share of the hold in the leg
  Pose legs;                          // scratch: walking-in-place's pose (no meaning between frames)
  std::vector<Transform> model_space;  // scratch: FK of the output
};
void reset(const Model& model, State& state);

struct Info {
  UpdateStatus upper = UpdateStatus::Ok;  // the upper-body method's status
  UpdateStatus legs = UpdateStatus::Ok;   // walking-in-place's status
  bool feet_tracked = false;              // both feet usable in this frame
  double legs_weight = 0;                 // share of walking-in-place in the leg joints
  bool walking = false;
  double speed = 0, distance = 0, heading = 0;  // walking-in-place: m/s, m, radians (0 = +z)
  std::array<bool, 2> foot_locked{false, false};
  accent::MatchStatus match = accent::MatchStatus::Matched;  // with a database
};

// One frame: head and hands drive the upper body, the feet the legs. `out`
// must have the model skeleton's joint count (else Rejected). Rejected frames
// (non-finite or backward time) leave state and `out` untouched; no
// allocation, exceptions or I/O.
UpdateStatus update(const Model& model, const TrackerFrame& frame, State& state, PoseRef out, Info* info = nullptr);

// This frame's Info as named fields (InfoFields: the server's pose "info",
// the C API's lw_avatar_info_field); allocates nothing.
void describe(const Info& info, InfoFields& out);

}  // namespace legwork::combined
