// legwork.combined: one avatar, two sources (accentuated or IK upper body,
// walking-in-place legs) on the per-frame contract.
#include "bindings.hpp"

#include <legwork/combined/combined.hpp>

namespace legwork::py {

void bind_combined(pb::module_& m) {
  using namespace pybind11::literals;
  using namespace legwork::combined;
  pb::class_<Settings>(m, "Settings", "Combined avatar options (legwork::combined::Settings; docs/combined.md).")
      .def(pb::init<>())
      .def_readwrite("blend_time", &Settings::blend_time, "seconds for the legs to fade between the sources")
      .def_readwrite("accent", &Settings::accent, "legwork.accent.Settings of the upper body (with a database)")
      .def_readwrite("ik", &Settings::ik, "legwork.ik.Settings of the upper body (without one)")
      .def_readwrite("wip", &Settings::wip, "legwork.wip.Settings of the legs");
  auto [model, state] = def_model_state<Model, State>(m, &reset, "Immutable combined model (upper body + legs on one skeleton).",
                                                      "One combined avatar's memory between frames.");
  model.def_property_readonly("accentuated", &Model::accentuated, "True: the upper body is accentuation over a database")
      .def_property_readonly("leg_joints", &Model::leg_joints, "joints driven by walking-in-place (hips down)");
  state.def_readonly("legs_weight", &State::legs_weight, "0 = the upper method's legs, 1 = walking-in-place's")
      .def_property_readonly("wip", [](State& s) -> wip::State& { return s.wip; }, pb::return_value_policy::reference_internal,
                             "the legs' walking-in-place state (legwork.wip.set_floor applies)");
  m.def("make_model", pb::overload_cast<const accent::Database&, const Settings&, const wip::LearnedMapping*>(&make_model), "db"_a,
        "settings"_a = Settings{}, "learned"_a = nullptr, pb::keep_alive<0, 1>(),
        "Upper body by accentuation over `db` (kept alive by the model), legs by walking-in-place. learned: the legs'\n"
        "table for settings.wip.mapping.depth = legwork.wip.DepthMapping.Learned (legwork.wip.read_learned_mapping).");
  m.def("make_model", pb::overload_cast<const Skeleton&, const Settings&, const wip::LearnedMapping*>(&make_model), "skeleton"_a,
        "settings"_a = Settings{}, "learned"_a = nullptr,
        "Upper body by the full-body IK avatar on `skeleton`, legs by walking-in-place (learned: as above).");
  def_fields(pb::class_<Info>(m, "Info", "Per-frame diagnostics.")
      .def(pb::init<>())
      .def_readonly("upper", &Info::upper, "the upper-body method's UpdateStatus")
      .def_readonly("legs", &Info::legs, "walking-in-place's UpdateStatus")
      .def_readonly("feet_tracked", &Info::feet_tracked)
      .def_readonly("legs_weight", &Info::legs_weight)
      .def_readonly("walking", &Info::walking)
      .def_readonly("speed", &Info::speed, "m/s")
      .def_readonly("distance", &Info::distance, "metres walked")
      .def_readonly("heading", &Info::heading, "radians about y, 0 = +z"));
  def_update(m, &update,
             "One frame: head and hands drive the upper body, the feet the legs; `out` (a legwork.core.Pose of\n"
             "model.skeleton()) written; returns legwork.core.UpdateStatus.");
}

}  // namespace legwork::py
