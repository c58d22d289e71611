// legwork.walkcycle: walk cycles from key-pose files and the frame-by-frame walker.
#include "bindings.hpp"

#include <legwork/walkcycle/cycle.hpp>
#include <legwork/walkcycle/offline/ground.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/walker.hpp>

namespace legwork::py {

void bind_walkcycle(pb::module_& m) {
  using namespace pybind11::literals;
  using namespace legwork::walkcycle;
  pb::class_<CycleModel>(m, "CycleModel", "A walk cycle built from four key poses (immutable).")
      .def_readonly("skeleton", &CycleModel::skeleton)
      .def_readonly("frames_per_cycle", &CycleModel::frames_per_cycle)
      .def_readonly("fps", &CycleModel::fps, "cycle frames per second");
  pb::class_<WalkKeys>(m, "WalkKeys", "Four key poses and timing of a walk (from a walk file).");
  pb::class_<WalkFile>(m, "WalkFile", "A walk file's skeleton and key poses.")
      .def_readonly("skeleton", &WalkFile::skeleton)
      .def_readonly("keys", &WalkFile::keys);
  m.def("load_walk", &load_walk, "walk_path"_a, "skeleton_bvh"_a = "",
        "A walk file (data/walks/*.json) and its skeleton (the BVH next to it, or skeleton_bvh); legwork.Error\n"
        "naming the file and field at fault.");
  m.def("build_cycle", &build_cycle, "skeleton"_a, "keys"_a, "The mirrored walk cycle of four key poses.");
  pb::enum_<Pivot>(m, "Pivot").value("Heel", Pivot::Heel).value("Ball", Pivot::Ball);
  pb::enum_<RootMotion>(m, "RootMotion", "How the root travels: Smooth (even speed, legs by IK) or Pivot (document 001).")
      .value("Smooth", RootMotion::Smooth)
      .value("Pivot", RootMotion::Pivot);
  pb::class_<Settings>(m, "Settings", "Walker options (legwork::walkcycle::Settings).")
      .def(pb::init<>())
      .def_readwrite("max_turn_per_step", &Settings::max_turn_per_step, "radians of heading change per step")
      .def_property(
          "start_position", [](const Settings& s) { return std::vector<double>{s.start_position.x(), s.start_position.y(), s.start_position.z()}; },
          [](Settings& s, const pb::handle& p) {
            const Array a = require_array(p, "start_position", {3}, "(3,) metres");
            s.start_position = Vec3(a.at(0), a.at(1), a.at(2));
          },
          "floor point under the root at the start, metres (y ignored)")
      .def_readwrite("start_heading", &Settings::start_heading, "radians about y, 0 = facing +z")
      .def_readwrite("root", &Settings::root, "RootMotion.Smooth (default: even travel, legs by IK) or RootMotion.Pivot")
      .def_readwrite("soft_reach", &Settings::soft_reach, "smooth root: fraction of a leg's length it may straighten to, (0, 1]")
      .def_readwrite("turn_on_ball", &Settings::turn_on_ball, "smooth root: the stance foot turns on its ball on turns (default True)")
      .def_readwrite("stairs_cadence", &Settings::stairs_cadence, "stairs: the cycle's rate on the flight, (0, 1] (default 0.8)")
      .def(
          "set_ground", [](Settings& s, const std::string& json) { s.ground = parse_ground_json(json, "Settings.set_ground"); },
          "json"_a,
          "The ground walked on: the JSON text of a path file's \"ground\" object (slope, heightfield or stairs);\n"
          "legwork.Error naming the field at fault.")
      .def_property_readonly("ground", [](const Settings& s) { return s.ground.describe(); },
                             "the ground walked on, described: 'flat', 'slope 12.0 % over 4.00 m', 'height field ...'");
  def_model_state<Model, State>(m, static_cast<void (*)(const Model&, State&)>(&reset), "Immutable walker model (owns its cycle).",
                                "One walker's memory between frames.")
      .first.def("cycle", &Model::cycle, pb::return_value_policy::reference_internal);
  m.def("make_model", &make_model, "cycle"_a, "settings"_a = Settings{}, "Walker from a cycle.");
  def_fields(pb::class_<Info>(m, "Info", "Per-frame diagnostics.")
      .def(pb::init<>())
      .def_readonly("step", &Info::step)
      .def_readonly("cycle_time", &Info::cycle_time, "cycle frames since the start")
      .def_readonly("heading", &Info::heading, "radians")
      .def_readonly("desired_heading", &Info::desired_heading, "radians")
      .def_readonly("left_planted", &Info::left_planted)
      .def_readonly("pivot", &Info::pivot)
      .def_readonly("pelvis_drop", &Info::pelvis_drop, "smooth root: metres the pelvis is lowered so the legs reach")
      .def_readonly("foot_roll", &Info::foot_roll, "smooth root: largest roll of a foot out of reach, radians")
      .def_readonly("reach_limited", &Info::reach_limited, "smooth root: a leg needed more than soft_reach")
      .def_readonly("ground_rise", &Info::ground_rise, "smooth root: metres the pelvis is raised by the ground under the feet")
      .def_readonly("cadence", &Info::cadence, "the cycle's rate (1; Settings.stairs_cadence on stairs)"));
  def_update(m, &update,
             "One frame: the head device's yaw steers (held when not usable); the walk advances by the frame's dt;\n"
             "`out` (a legwork.core.Pose of model.skeleton()) gets the world pose; returns legwork.core.UpdateStatus.");
}

}  // namespace legwork::py
