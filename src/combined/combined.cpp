#include <legwork/combined/combined.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace legwork::combined {

void Model::finish() {
  if (!(settings_.blend_time > 0) || !std::isfinite(settings_.blend_time))
    throw Error("combined: blend_time " + std::to_string(settings_.blend_time) + " s must be positive");
  const Skeleton& skel = skeleton();
  wip_.emplace(wip::make_model(skel, settings_.wip));
  for (Role hip : {Role::LeftHip, Role::RightHip})
    if (!skel.roles.has(hip)) throw Error("combined: the avatar skeleton has no " + std::string(role_name(hip)) + " joint");
  for (int j = 0; j < skel.joint_count(); ++j)
    for (Role hip : {Role::LeftHip, Role::RightHip})
      if (skel.is_ancestor(skel.roles[hip], j) || j == skel.roles[hip]) {
        leg_joints_.push_back(j);
        break;
      }
}

Model make_model(const accent::Database& db, const Settings& settings) {
  Model m;
  m.settings_ = settings;
  m.accent_.emplace(accent::make_model(db, settings.accent));
  m.finish();
  return m;
}

Model make_model(const Skeleton& skeleton, const Settings& settings) {
  Model m;
  m.settings_ = settings;
  m.ik_.emplace(ik::make_model(skeleton, settings.ik));
  m.finish();
  return m;
}

State::State(const Model& model) : wip(model.wip()), legs(model.skeleton()) {
  if (model.accent()) accent.emplace(*model.accent());
  if (model.ik()) ik.emplace(*model.ik());
}

void reset(const Model& model, State& state) {
  state.clock = FrameClock{};
  if (state.accent) accent::reset(*model.accent(), *state.accent);
  if (state.ik) ik::reset(*model.ik(), *state.ik);
  wip::reset(model.wip(), state.wip);
  state.legs_weight = 0;
}

namespace {

UpdateStatus worst(UpdateStatus a, UpdateStatus b) {
  if (a == UpdateStatus::Restarted || b == UpdateStatus::Restarted) return UpdateStatus::Restarted;
  if (a == UpdateStatus::Degraded || b == UpdateStatus::Degraded) return UpdateStatus::Degraded;
  return UpdateStatus::Ok;
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
  if (info) {
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

}  // namespace legwork::combined
