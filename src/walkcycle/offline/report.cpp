// Reports of the walk-cycle generator (see report.hpp).
#include <legwork/walkcycle/offline/report.hpp>

#include <legwork/walkcycle/keys.hpp>

#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace legwork::walkcycle {

using nlohmann::json;

namespace {
// printf into a string (summary lines).
void appendf(std::string& s, const char* fmt, ...) {
  char buf[512];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  s += buf;
}
}  // namespace

double round6(double v) { return std::round(v * 1e6) / 1e6 + 0.0; }

json cycle_report(const CycleModel& model, const std::string& name, std::string& text) {
  const auto seam = measure_loop_seam(model);
  const auto feet = key_foot_heights(model);
  appendf(text, "cycle: %d frames, step length %.3f m, loop seam %.2e m / %.2e m/s\n", model.frames_per_cycle,
          step_length(model), seam.position_m, seam.velocity_mps);
  json report;
  report["walk"] = name;
  report["frames_per_cycle"] = model.frames_per_cycle;
  report["fps"] = model.fps;
  report["step_length_m"] = round6(step_length(model));
  report["loop_seam_error"] = seam.position_m;  // metres (position; velocity below)
  report["loop_seam_error_m"] = seam.position_m;
  report["loop_seam_velocity_error_mps"] = seam.velocity_mps;
  report["key_frames"] = {model.key_frames[0], model.key_frames[1], model.key_frames[2], model.key_frames[3]};
  report["key_foot_height_mm"] = json::array();
  for (double h : feet) report["key_foot_height_mm"].push_back(round6(h * 1e3));
  const auto floor = cycle_floor_contact(model);
  report["cycle_lowest_foot_mm"] = round6(floor.lowest_m * 1e3);
  report["cycle_lowest_foot_frame"] = floor.at_frame;
  report["floor_clamp"] = model.floor_clamp;
  report["floor_lift_mm_max"] = round6(floor.max_lift_m * 1e3);
  report["floor_lift_frame"] = floor.lift_frame;
  if (floor.max_lift_m > 0.01) {
    // The keys touch the floor; the spline between two of them does not know
    // about it (a foot rolling from heel to flat between contact and down
    // dips through it). Say between which keys, what was done, what to do.
    const char* names[] = {"contact", "down", "pass", "up", "contact"};
    const double in_step = std::fmod(floor.lift_frame, model.half_cycle());
    int k = 0;
    while (k < 3 && in_step >= model.key_frames[static_cast<std::size_t>(k + 1)]) ++k;
    if (model.floor_clamp)
      appendf(text, "floor: the keys touch the floor; between the %s and %s keys (frame %.2f) the spline alone would take a "
              "foot %.0f mm lower, which the loop takes up by lifting the root and a walk by its legs, so nothing goes "
              "through the floor\n",
              names[k], names[k + 1], floor.lift_frame, floor.max_lift_m * 1e3);
    else
      appendf(text, "floor: between the %s and %s keys the interpolated foot dips %.0f mm below the floor (frame %.2f); "
              "floor_clamp is off: the in-place loop and the pivoting root go through the floor\n",
              names[k], names[k + 1], floor.max_lift_m * 1e3, floor.lift_frame);
  }
  return report;
}

void add_walk_report(const CycleModel& model, const WalkResult& w, double ms, json& report, std::string& text) {
  const auto slip = measure_stance_slip(model, w.motion, w.labels, w.ground);
  appendf(text,
          "walk: %d steps, %d frames at %g fps (%.1f ms), path %.2f m, turning %.1f deg, end %.3f m from the path's end, "
          "facing %.1f deg off its end tangent; travelled %.3f m, max deviation %.3f m\n",
          w.steps, w.motion.frame_count(), w.motion.fps, ms, w.path_length, rad2deg(w.turning), w.end_distance,
          rad2deg(w.end_heading_error), w.travel, w.max_path_deviation);
  appendf(text, "stance slip: max %.2e mm, mean %.2e mm over %d pivot phases\n", slip.max_mm, slip.mean_mm, slip.phases);
  report["steps"] = w.steps;
  report["frames"] = w.motion.frame_count();
  report["output_fps"] = w.motion.fps;
  report["stance_slip_mm_max"] = slip.max_mm;
  report["stance_slip_mm_mean"] = slip.mean_mm;
  report["stance_phases"] = slip.phases;
  report["path_length_m"] = round6(w.path_length);
  report["turning_deg"] = round6(rad2deg(w.turning));
  report["turning_abs_deg"] = round6(rad2deg(w.turning_abs));
  report["end_distance_m"] = round6(w.end_distance);
  report["end_position_m"] = {round6(w.end_position.x()), round6(w.end_position.z())};
  report["end_heading_error_deg"] = round6(rad2deg(w.end_heading_error));
  report["travel_m"] = round6(w.travel);
  const auto rm = measure_root_motion(w.motion, w.labels);
  report["root_speed_min_mps"] = round6(rm.speed_min_mps);
  report["root_speed_mean_mps"] = round6(rm.speed_mean_mps);
  report["root_speed_max_mps"] = round6(rm.speed_max_mps);
  report["root_accel_max_mps2"] = round6(rm.accel_max_mps2);
  report["pelvis_vertical_speed_max_mps"] = round6(rm.vertical_speed_max_mps);
  report["pelvis_vertical_accel_max_mps2"] = round6(rm.vertical_accel_max_mps2);
  report["max_path_deviation_m"] = round6(w.max_path_deviation);
  report["root_motion"] = w.root == RootMotion::Smooth ? "smooth" : "pivot";
  const auto contact = measure_ground_contact(model, w.motion, w.labels, w.ground);
  report["ground"] = w.ground.describe();
  report["ground_penetration_mm_max"] = round6(contact.penetration_mm);
  report["ground_penetration_frame"] = contact.penetration_frame;
  report["stance_float_mm_max"] = round6(contact.stance_float_mm);
  report["stance_float_frame"] = contact.float_frame;
  appendf(text, "ground: %s; feet at most %.2f mm below it (frame %d), the stance foot at most %.2f mm above it (frame %d)\n",
          w.ground.describe().c_str(), contact.penetration_mm, contact.penetration_frame, contact.stance_float_mm,
          contact.float_frame);
  if (w.ground.stepped()) {
    const auto treads = measure_treads(model, w.motion, w.labels, w.ground);
    report["tread_ball_margin_mm_min"] = round6(treads.ball_margin_mm);
    report["treads_per_step_max"] = treads.treads_per_step_max;
    report["stairs_stride_m"] = round6(w.stairs_stride);
    appendf(text, "stairs: %s; the stance foot's ball at least %.1f mm from a tread's edge, up to %d tread%s per step\n",
            w.stairs_stride > 0 ? ("strides shortened to " + std::to_string(std::lround(w.stairs_stride * 1000)) + " mm on the flight").c_str()
                                : "the walk's own stride",
            treads.ball_margin_mm, treads.treads_per_step_max, treads.treads_per_step_max == 1 ? "" : "s");
  }
  const auto turn = measure_foot_turning(model, w.motion, w.labels, w.ground);
  report["stance_heel_slip_mm_max"] = round6(turn.heel_slip_mm);
  report["stance_ball_slip_mm_max"] = round6(turn.ball_slip_mm);
  report["stance_twist_deg_max"] = round6(turn.twist_deg);
  report["stance_twist_step"] = turn.worst_step;
  report["stance_turn_on_ball_deg_max"] = round6(turn.turn_on_ball_deg);
  appendf(text, "stance foot (heel / ball down within %.0f mm of the ground): heel slips up to %.2f mm, ball %.2f mm; "
          "a flat foot twists up to %.2f deg (step %d); turns up to %.1f deg on its ball\n",
          kFootDownTolerance * 1e3, turn.heel_slip_mm, turn.ball_slip_mm, turn.twist_deg, turn.worst_step,
          turn.turn_on_ball_deg);
  report["foot_roll_max_deg"] = round6(rad2deg(w.foot_roll_max));
  report["pelvis_drop_max_m"] = round6(w.pelvis_drop_max);
  report["leg_reach_max"] = round6(w.leg_reach_max);
  report["reach_limited_frames"] = w.reach_limited_frames;
  report["foot_lifted_out_of_ground_mm_max"] = round6(w.ground_lift_max * 1e3);
  appendf(text, "root: %s, speed %.2f-%.2f m/s (mean %.2f), peak acceleration %.1f m/s^2; pelvis vertical speed up to %.2f m/s, "
          "acceleration up to %.1f m/s^2",
          w.root == RootMotion::Smooth ? "smooth (legs by IK)" : "pivoting (document 001)", rm.speed_min_mps,
          rm.speed_max_mps, rm.speed_mean_mps, rm.accel_max_mps2, rm.vertical_speed_max_mps, rm.vertical_accel_max_mps2);
  if (w.root == RootMotion::Smooth)
    appendf(text, "; feet roll up to %.1f deg and the pelvis drops up to %.1f mm to stay in reach, legs reach up to %.1f %% of their length (softened on %d frames)",
            rad2deg(w.foot_roll_max), 1e3 * w.pelvis_drop_max, 100 * w.leg_reach_max, w.reach_limited_frames);
  text += "\n";
  json steps = json::array();
  for (const auto& s : w.footsteps)
    steps.push_back({{"step", s.step}, {"frame", s.frame}, {"foot", s.left ? "left" : "right"},
                     {"heel", {round6(s.heel.x()), round6(s.heel.z())}}, {"heading_deg", round6(rad2deg(s.heading))}});
  report["footsteps"] = steps;
}

void add_in_place_report(const Motion& cycle, json& report) {
  report["steps"] = 2;
  report["frames"] = cycle.frame_count();
  report["stance_slip_mm_max"] = nullptr;  // in place: the feet slide by design
}

ArcFigures arc_figures(const CycleModel& m, const std::string& joint_name) {
  ArcFigures a;
  a.joint = find_joint_or_role(m.skeleton, joint_name);
  if (a.joint < 0) throw Error("--arc: unknown joint '" + joint_name + "'");
  a.name = m.skeleton.names[static_cast<std::size_t>(a.joint)];
  a.arc = trace_arc(m, a.joint, 1);
  a.fine = trace_arc(m, a.joint, 4);
  a.smooth = arc_smoothness(a.fine);
  a.jerky = a.smooth.jerk_ratio > 5.0 && a.smooth.extent_m > 0.1;  // (a hand held still has a tiny, noisy arc)
  return a;
}

std::string arc_csv(const ArcFigures& a) {
  std::string csv = "frame,x,y,z,key\n";
  const char* key_names[] = {"contact", "down", "pass", "up", "contact2", "down2", "pass2", "up2"};
  for (std::size_t i = 0; i < a.arc.points.size(); ++i) {
    std::string key;
    for (std::size_t k = 0; k < a.arc.key_indices.size(); ++k)
      if (a.arc.key_indices[k] == static_cast<int>(i)) key = key_names[k];
    appendf(csv, "%zu,%.6f,%.6f,%.6f,%s\n", i, a.arc.points[i].x(), a.arc.points[i].y(), a.arc.points[i].z(), key.c_str());
  }
  return csv;
}

std::string arc_title(const ArcFigures& a) {
  std::string t;
  appendf(t, "%s arc over the cycle - jerk ratio %.2f (frame %.1f), curvature jump %.0f deg", a.name.c_str(),
          a.smooth.jerk_ratio, a.smooth.jerk_frame, a.smooth.max_curvature_jump_deg);
  return t.substr(0, 199);
}

std::string arc_summary(const ArcFigures& a) {
  std::string t;
  appendf(t, "arc %s: spans %.2f m, jerk ratio %.2f at frame %.1f (its sharpest change of acceleration over the "
          "arc's typical one, docs/walkcycle.md), largest curvature jump %.1f deg at frame %.1f%s\n",
          a.name.c_str(), a.smooth.extent_m, a.smooth.jerk_ratio, a.smooth.jerk_frame, a.smooth.max_curvature_jump_deg,
          a.smooth.jump_frame, a.jerky ? "  <- jerky: check the keys near this frame" : "");
  return t;
}

json arc_report(const ArcFigures& a, const std::string& csv_path) {
  return {{"joint", a.name},
          {"extent_m", round6(a.smooth.extent_m)},
          {"jerky", a.jerky},
          {"jerk_ratio", round6(a.smooth.jerk_ratio)},
          {"jerk_frame", round6(a.smooth.jerk_frame)},
          {"max_curvature_jump_deg", round6(a.smooth.max_curvature_jump_deg)},
          {"jump_frame", round6(a.smooth.jump_frame)},
          {"csv", csv_path}};
}

json extraction_report(const Extraction& ex, const Motion& clip, const std::string& clip_path) {
  json r;
  r["clip"] = clip_path;
  r["frames"] = clip.frame_count();
  r["fps"] = clip.fps;
  r["cycle_seconds"] = round6(ex.cycle_seconds);
  r["steps_found"] = ex.steps.size();
  r["steps_used"] = ex.steps_used;
  r["resynthesis_mean_mm"] = round6(ex.resynthesis_mean_mm);
  r["resynthesis_max_mm"] = round6(ex.resynthesis_max_mm);
  r["flight_fraction"] = round6(ex.flight_fraction);
  r["warning"] = ex.warning;
  json steps = json::array();
  for (const auto& s : ex.steps)
    steps.push_back({{"foot", s.left ? "left" : "right"}, {"contact", s.contact}, {"down", s.down}, {"pass", s.pass},
                     {"up", s.up}, {"next_contact", s.next_contact}, {"used", s.used}});
  r["steps"] = steps;
  return r;
}

std::string extraction_summary(const Extraction& ex, const WalkKeys& keys) {
  std::string t;
  appendf(t, "%zu steps found (%d used), cycle %.3f s -> %d frames at %g fps; timing down %.2f pass %.2f up %.2f\n",
          ex.steps.size(), ex.steps_used, ex.cycle_seconds, keys.frames_per_cycle, keys.fps, keys.key_frames[1],
          keys.key_frames[2], keys.key_frames[3]);
  appendf(t, "both feet off the floor in %.0f %% of the steady steps' frames\n", ex.flight_fraction * 100);
  appendf(t, "resynthesis vs the clip's mean cycle: joint positions %.1f mm mean, %.1f mm max\n", ex.resynthesis_mean_mm,
          ex.resynthesis_max_mm);
  return t;
}

}  // namespace legwork::walkcycle
