#include <legwork/combined/combined.hpp>

#include <legwork/core/fk.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace legwork::combined {

void Model::finish(const wip::LearnedMapping* learned) {
  if (!(settings_.blend_time > 0) || !std::isfinite(settings_.blend_time))
    throw Error("combined: blend_time " + std::to_string(settings_.blend_time) + " s must be positive");
  if (!(settings_.unlock_time > 0) || !std::isfinite(settings_.unlock_time))
    throw Error("combined: unlock_time " + std::to_string(settings_.unlock_time) + " s must be positive");
  const Skeleton& skel = skeleton();
  wip_.emplace(wip::make_model(skel, settings_.wip, {}, learned));
  for (Role hip : {Role::LeftHip, Role::RightHip})
    if (!skel.roles.has(hip)) throw Error("combined: the avatar skeleton has no " + std::string(role_name(hip)) + " joint");
  legs_ = {ik::left_leg(skel), ik::right_leg(skel)};
  for (int j = 0; j < skel.joint_count(); ++j)
    for (Role hip : {Role::LeftHip, Role::RightHip})
      if (skel.is_ancestor(skel.roles[hip], j) || j == skel.roles[hip]) {
        leg_joints_.push_back(j);
        break;
      }
}

Model make_model(const accent::Database& db, const Settings& settings, const wip::LearnedMapping* learned) {
  Model m;
  m.settings_ = settings;
  m.accent_.emplace(accent::make_model(db, settings.accent));
  m.finish(learned);
  return m;
}

Model make_model(const Skeleton& skeleton, const Settings& settings, const wip::LearnedMapping* learned) {
  Model m;
  m.settings_ = settings;
  m.ik_.emplace(ik::make_model(skeleton, settings.ik));
  m.finish(learned);
  return m;
}

State::State(const Model& model)
    : wip(model.wip()), legs(model.skeleton()), model_space(static_cast<std::size_t>(model.skeleton().joint_count())) {
  if (model.accent()) accent.emplace(*model.accent());
  if (model.ik()) ik.emplace(*model.ik());
}

void reset(const Model& model, State& state) {
  state.clock = FrameClock{};
  if (state.accent) accent::reset(*model.accent(), *state.accent);
  if (state.ik) ik::reset(*model.ik(), *state.ik);
  wip::reset(model.wip(), state.wip);
  state.legs_weight = 0;
  state.locked = state.released = {false, false};
  state.lock_weight = {0, 0};
}

namespace {

UpdateStatus worst(UpdateStatus a, UpdateStatus b) {
  if (a == UpdateStatus::Restarted || b == UpdateStatus::Restarted) return UpdateStatus::Restarted;
  if (a == UpdateStatus::Degraded || b == UpdateStatus::Degraded) return UpdateStatus::Degraded;
  return UpdateStatus::Ok;
}

// Holds each walking-in-place stance foot where it touched down while the root
// travels (see Settings::foot_lock).
void lock_feet(const Model& model, const wip::Info& wi, bool feet, double dt, State& state, PoseRef out,
               std::array<bool, 2>& locked_out) {
  const Skeleton& skel = model.skeleton();
  forward_kinematics(skel, out, state.model_space);
  for (int foot = 0; foot < 2; ++foot) {
    const auto f = static_cast<std::size_t>(foot);
    const ik::TwoBoneChain& leg = model.leg(foot);
    if (leg.root < 0 || leg.mid < 0 || leg.end < 0) continue;
    const Vec3 ankle = state.model_space[static_cast<std::size_t>(leg.end)].translation;
    const Vec3 hip = state.model_space[static_cast<std::size_t>(leg.root)].translation;
    const double reach = (state.model_space[static_cast<std::size_t>(leg.mid)].translation - hip).norm() +
                         (ankle - state.model_space[static_cast<std::size_t>(leg.mid)].translation).norm();
    const bool down = feet && !wip::in_swing(wi.phase[f]);
    if (!down || state.lock_weight[f] <= 0) state.released[f] = false;  // lifted, or faded back: may hold again
    if (down && state.locked[f] && (state.lock_at[f] - hip).norm() > 0.995 * reach) state.released[f] = true;  // let go, no jump
    if (down && !state.released[f]) {
      if (!state.locked[f]) state.lock_at[f] = ankle;  // touch-down: hold it here
      state.locked[f] = true;
      state.lock_weight[f] = 1.0;
    } else {
      state.locked[f] = false;
      state.lock_weight[f] = std::max(0.0, state.lock_weight[f] - dt / model.settings().unlock_time);
    }
    locked_out[f] = state.locked[f];
    if (state.lock_weight[f] <= 0) continue;
    ik::TwoBoneTarget target;
    target.position = state.lock_at[f];
    // Position only: holding the ankle's rotation too (the sole fixed) measured worse
    // on the 57 shared walks (foot skating 1.11 against 1.03 cm/frame): the foot rolls in stance.
    target.position_weight = state.lock_weight[f] * state.legs_weight;
    target.hint_weight = 0;  // keep walking-in-place's bend plane
    ik::solve_two_bone(skel, leg, target, out, state.model_space);
  }
}

}  // namespace

UpdateStatus update(const Model& model, const TrackerFrame& frame, State& state, PoseRef out, Info* info) {
  if (out.joint_count() != model.skeleton().joint_count()) return UpdateStatus::Rejected;
  const FrameClock before = state.clock;
  const FrameClock::Step step = state.clock.advance(frame.time);
  if (step.verdict == FrameClock::Verdict::Reject) return UpdateStatus::Rejected;
  accent::Info ai;
  const UpdateStatus upper = model.accent() ? accent::update(*model.accent(), frame, *state.accent, out, &ai)
                                            : ik::update(*model.ik(), frame, *state.ik, out, nullptr);
  if (upper == UpdateStatus::Rejected) {  // the upper method refused a frame our clock took: stay as before
    state.clock = before;
    return UpdateStatus::Rejected;
  }
  wip::Info wi;
  const UpdateStatus legs = wip::update(model.wip(), frame, state.wip, state.legs.ref(), &wi);
  const bool feet = usable(frame.foot(kLeft)) && usable(frame.foot(kRight)) && legs != UpdateStatus::Rejected;
  // Fade toward the source that has data; a restart starts from the upper method's legs.
  if (step.verdict == FrameClock::Verdict::Restart) state.legs_weight = 0;
  const double rate = step.verdict == FrameClock::Verdict::Accept ? step.dt / model.settings().blend_time : 0.0;
  state.legs_weight = std::clamp(state.legs_weight + (feet ? rate : -rate), 0.0, 1.0);
  const double w = state.legs_weight;
  if (w > 0)
    for (int j : model.leg_joints()) {
      const auto ju = static_cast<std::size_t>(j);
      out.rotations[ju] = out.rotations[ju].slerp(w, state.legs.rotations[ju]).normalized();
    }
  std::array<bool, 2> locked{false, false};
  if (model.settings().foot_lock && w > 0) lock_feet(model, wi, feet, step.verdict == FrameClock::Verdict::Accept ? step.dt : 0.0, state, out, locked);
  else state.locked = {false, false}, state.lock_weight = {0, 0};
  if (info) {
    info->foot_locked = locked;
    info->upper = upper;
    info->legs = legs;
    info->feet_tracked = feet;
    info->legs_weight = w;
    info->walking = wi.walking;
    info->speed = wi.speed;
    info->distance = wi.distance;
    info->heading = wi.heading;
    info->match = ai.match;
  }
  const UpdateStatus both = worst(upper, legs == UpdateStatus::Rejected ? UpdateStatus::Degraded : legs);
  return both == UpdateStatus::Ok && !feet ? UpdateStatus::Degraded : both;
}

void describe(const Info& i, InfoFields& out) {
  add_walking(out, i.walking, i.speed, i.distance, i.heading);
  out.add("legs", i.feet_tracked ? "wip" : "upper");
  out.add("legs_weight", i.legs_weight);
}

}  // namespace legwork::combined
