// legwork.ik: the full-body IK avatar (VRIK-style baseline) on the per-frame contract.
#include "bindings.hpp"

#include <legwork/ik/full_body.hpp>

namespace legwork::py {

void bind_ik(pb::module_& m) {
  using namespace pybind11::literals;
  using namespace legwork::ik;
  pb::class_<Settings>(m, "Settings", "Full-body IK options (legwork::ik::Settings; metres, seconds, radians).")
      .def(pb::init<>())
      .def_readwrite("floor_height", &Settings::floor_height, "metres: the play-area floor")
      .def_readwrite("crouch_leg_share", &Settings::crouch_leg_share)
      .def_readwrite("min_pelvis_fraction", &Settings::min_pelvis_fraction)
      .def_readwrite("pelvis_lean_share", &Settings::pelvis_lean_share)
      .def_readwrite("hands_heading_weight", &Settings::hands_heading_weight)
      .def_readwrite("pelvis_turn_rate", &Settings::pelvis_turn_rate, "1/s")
      .def_readwrite("neck_share", &Settings::neck_share)
      .def_readwrite("clavicle_reach", &Settings::clavicle_reach, "radians")
      .def_readwrite("body_reach", &Settings::body_reach, "radians")
      .def_readwrite("balance_head_weight", &Settings::balance_head_weight)
      .def_readwrite("step_threshold", &Settings::step_threshold, "metres")
      .def_readwrite("foot_distance_threshold", &Settings::foot_distance_threshold, "metres")
      .def_readwrite("step_angle_threshold", &Settings::step_angle_threshold, "radians")
      .def_readwrite("step_speed", &Settings::step_speed, "m/s")
      .def_readwrite("swing_speed_ratio", &Settings::swing_speed_ratio)
      .def_readwrite("min_step_time", &Settings::min_step_time, "seconds")
      .def_readwrite("max_step_time", &Settings::max_step_time, "seconds")
      .def_readwrite("step_height", &Settings::step_height, "metres")
      .def_readwrite("velocity_lead", &Settings::velocity_lead)
      .def_readwrite("max_step_length", &Settings::max_step_length, "metres");
  def_model_state<Model, State>(m, &reset, "Immutable full-body IK model of a skeleton (copied).",
                                "One IK avatar's memory between frames.")
      .first.def_property_readonly("standing_head_height", &Model::standing_head_height, "metres")
      .def_property_readonly("standing_pelvis_height", &Model::standing_pelvis_height, "metres");
  m.def("make_model", &make_model, "skeleton"_a, "settings"_a = Settings{},
        "Model from a skeleton with head, hands and legs; legwork.Error naming missing roles.");
  def_fields(pb::class_<Info>(m, "Info", "Per-frame diagnostics.")
      .def(pb::init<>())
      .def_readonly("steps_taken", &Info::steps_taken)
      .def_readonly("stepping", &Info::stepping, "[left, right]: foot in the air")
      .def_readonly("chest_yaw", &Info::chest_yaw, "radians about y")
      .def_readonly("pelvis_yaw", &Info::pelvis_yaw, "radians about y")
      .def_readonly("lean", &Info::lean, "radians")
      .def_readonly("head_tracked", &Info::head_tracked)
      .def_readonly("hand_tracked", &Info::hand_tracked));
  def_update(m, &update,
             "One frame: head and hands of `frame` in (the head placed exactly, wrists when in reach, legs step);\n"
             "`out` (a legwork.core.Pose of model.skeleton()) written; returns legwork.core.UpdateStatus.");
}

}  // namespace legwork::py
