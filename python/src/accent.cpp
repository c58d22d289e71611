// legwork.accent: databases (build, load, save), Settings/Model/State/Info/update, whole-clip runs.
#include "bindings.hpp"

#include <legwork/accent/accent.hpp>
#include <legwork/accent/database.hpp>
#include <legwork/accent/offline/builder.hpp>
#include <legwork/accent/offline/report.hpp>
#include <legwork/accent/offline/run.hpp>

namespace legwork::py {
namespace {
namespace accent_binding {

using namespace pybind11::literals;
using namespace legwork::accent;

Database build(const std::string& folder, const std::vector<std::string>& classes, const std::vector<std::string>& exclude,
               double fps, int hop, int speed_variants, bool mirror) {
  require_rate(fps, "fps");
  if (hop < 1) value_error("hop: expected samples between window ends >= 1, got " + std::to_string(hop));
  if (speed_variants < 0) value_error("speed_variants: expected >= 0, got " + std::to_string(speed_variants));
  const auto trials = load_trials(folder, classes, exclude);
  BuildConfig cfg;
  cfg.fps = fps;
  cfg.hop = hop;
  cfg.speed_variants = speed_variants;
  cfg.mirror = mirror;
  Database db = build_database(trials, cfg);
  db.build_index();
  return db;
}

void bind_database(pb::module_& m) {
  pb::class_<Database>(m, "Database",
                       "An accentuation database (read-only, memory-mapped when loaded). Shared by any number of models.")
      .def_property_readonly("window_count", &Database::window_count)
      .def_property_readonly("pose_count", &Database::pose_count)
      .def_property_readonly("classes", &Database::classes, "activity class names, list[str]")
      .def_property_readonly("skeleton", &Database::skeleton, pb::return_value_policy::reference_internal,
                             "the database skeleton (metres)")
      .def_property_readonly("height", &Database::height, "the database skeleton's standing height, metres")
      .def_property_readonly("fps", [](const Database& d) { return d.feature_space().fps; }, "the database (tracker) rate, Hz")
      .def_property_readonly("trials", [](const Database& d) {
        std::vector<std::string> files;
        for (const auto& t : d.trials()) files.push_back(t.file);
        return files;
      }, "source trial files, list[str]")
      .def_property_readonly("is_mapped", &Database::is_mapped)
      .def("info", [](const Database& d) { return pb::module_::import("json").attr("loads")(database_info(d).dump()); },
           "What the database holds, as `legwork info FILE.lwdb --json` prints it (without the file and load time): dict\n"
           "with format_version, bytes, windows, poses, joints, height_m, fps, hop, window_samples, window_stride,\n"
           "window_seconds, speeds, mirrored, correlation_threshold, typical_distance, search_index, classes (name,\n"
           "windows, trials) and trials (file, class, subject, trial, hand_foot_correlation).")
      .def("save", [](const Database& d, const std::string& path) { save_database(path, d); }, "path"_a,
           "Writes the database file (.lwdb).");
  m.def(
      "load_database",
      [](const std::string& path, bool verify_checksum) {
        LoadOptions opt;
        opt.verify_checksum = verify_checksum;
        return load_database(path, opt);
      },
      "path"_a, "verify_checksum"_a = true,
      "Memory-maps a .lwdb file; legwork.Error naming the file if missing, truncated, corrupted or of another version.");
  m.def("build_database", &build, "folder"_a, "classes"_a = std::vector<std::string>{}, "exclude"_a = std::vector<std::string>{},
        "fps"_a = 90.0, "hop"_a = 4, "speed_variants"_a = 2, "mirror"_a = false,
        "Builds a database in memory from a folder laid out like data/cmu (MANIFEST.tsv or bvh/<class>/*.bvh), as\n"
        "`legwork accent build` does; classes: [] = all; exclude: trial files to leave out (manifest path or name);\n"
        "fps: tracker rate (Hz); hop: samples between window ends; speed_variants: re-timed copies per window.");
}

void bind_settings(pb::module_& m) {
  pb::enum_<SearchMode>(m, "SearchMode")
      .value("BruteForce", SearchMode::BruteForce)
      .value("Exact", SearchMode::Exact)
      .value("Fast", SearchMode::Fast);
  pb::class_<Settings>(m, "Settings", "Accentuation options (the C++ legwork::accent::Settings; docs/accent.md).")
      .def(pb::init<>())
      .def_readwrite("search", &Settings::search)
      .def_readwrite("fast_eps", &Settings::fast_eps, "Fast search: KD-tree pruning slack")
      .def_readwrite("fast_max_checks", &Settings::fast_max_checks)
      .def_readwrite("k_left", &Settings::k_left, "matches for the left hand (1..32)")
      .def_readwrite("k_right", &Settings::k_right, "matches for the right hand (1..32)")
      .def_readwrite("threshold", &Settings::threshold, "match distance limit in typical-distance units; <= 0: none")
      .def_readwrite("align", &Settings::align)
      .def_readwrite("smooth", &Settings::smooth)
      .def_readwrite("smooth_halflife", &Settings::smooth_halflife, "seconds; 0 = EWMA only")
      .def_readwrite("min_smoothing_weight", &Settings::min_smoothing_weight)
      .def_readwrite("user_height", &Settings::user_height, "metres; 0 = the database skeleton's height")
      .def_readwrite("exaggeration", &Settings::exaggeration, "hands scaled about the head before matching (> 0)")
      .def_readwrite("classes", &Settings::classes, "classes to match, list[str] ([] = all)")
      .def_readwrite("recognize_class", &Settings::recognize_class,
                     "with several classes allowed: recognise the activity from the input (with hysteresis) and search only its class")
      .def_readwrite("class_seconds", &Settings::class_seconds, "smoothing of the per-class match costs, seconds")
      .def_readwrite("class_margin", &Settings::class_margin, "relative cost margin another class needs to take over (0..1)")
      .def_readwrite("class_hold_seconds", &Settings::class_hold_seconds, "seconds another class must stay better before a switch")
      .def_readwrite("joint_limits", &Settings::joint_limits)
      .def_readwrite("drive_head", &Settings::drive_head)
      .def_readwrite("fallback_seconds", &Settings::fallback_seconds, "seconds")
      .def_readwrite("hand_ik", &Settings::hand_ik, "0..1: wrists pulled onto the controllers")
      .def_readwrite("direct_only", &Settings::direct_only)
      .def_readwrite("max_head_tilt_deg", &Settings::max_head_tilt_deg, "degrees; 0 = off")
      .def_readwrite("foot_lock", &Settings::foot_lock, "hold planted feet (database contacts) by two-bone leg IK")
      .def_readwrite("contact_on", &Settings::contact_on, "blended contact above which a foot locks (0..1)")
      .def_readwrite("contact_off", &Settings::contact_off, "blended contact below which it lets go (0..1)")
      .def_readwrite("foot_release_seconds", &Settings::foot_release_seconds, "seconds to blend out of a lock")
      .def_readwrite("foot_lift_height", &Settings::foot_lift_height,
                     "metres (0..0.5) a foot released at the end of a contact is lifted on its way back (0 = slides)")
      .def_readwrite("foot_lock_hold_seconds", &Settings::foot_lock_hold_seconds,
                     "seconds a planted foot stays put before it creeps after the synthesized foot (0 = it creeps from touch-down)")
      .def_readwrite("foot_lock_slack", &Settings::foot_lock_slack,
                     "metres the synthesized foot may move from a planted foot before the plant creeps after it (0 = it always creeps)")
      .def_readwrite("foot_swing_speed", &Settings::foot_swing_speed,
                     "m/s above which a free foot counts as swinging and is lifted to clear the floor by foot_lift_height (0 = off)")
      .def_readwrite("travel_weight", &Settings::travel_weight,
                     "weight (0..100) of the user's head travel (horizontal speed over 0.2 and 0.6 s, vertical velocity, "
                     "height over body height) against the hand features when ranking candidates (0 = hand features only)")
      .def_readwrite("max_head_height_diff", &Settings::max_head_height_diff,
                     "while the user stands upright, reject candidates whose head is lower than the user's by more than "
                     "this share of body height; while the user is lower, those whose head is higher by more, unless "
                     "none would be left (0..2; 0 = off)")
      .def_readwrite("smooth_feedforward", &Settings::smooth_feedforward,
                     "share (0..1) of the matched candidates' own motion the smoothing plays forward, so a moving body "
                     "does not trail its target (0 = the filters pull toward a still target and lag)")
      .def_readwrite("lying_root_smoothing", &Settings::lying_root_smoothing,
                     "times (1..20) the spring's half-life on the root for a lying user (head at most 0.5 of their "
                     "height up), so a swimmer's feet do not wobble across the floor (1 = off)")
      .def_readwrite("lying_crown", &Settings::lying_crown,
                     "share (0..1) of a lying user's candidate turn taken from the headset (yaw from its crown, which "
                     "points away from the feet; roll from its face), and of the standing IK body taken out (0 = off)")
      .def_readwrite("other_class_cost", &Settings::other_class_cost,
                     "while the class is recognised (recognize_class, several classes allowed): the other allowed "
                     "classes are searched too, their distances times this factor (1..1e6; 1 = no preference); 0 = "
                     "the recognised class only")
      .def_readwrite("search_interval", &Settings::search_interval,
                     "seconds (0..1) between two searches of the database; in between each hand's matches are "
                     "continued in their trials (the last matches and their next windows, ranked by distance), as "
                     "motion matching does; 0 = search every frame")
      .def_readwrite("floor", &Settings::floor,
                     "feet never go through the floor (the knee bends; a foot pushed into it while moving slowly, or at any "
                     "speed while the user is bent over or lying or when pushed more than 5 cm in, stands on it); False: "
                     "they follow the synthesized pose below it too")
      .def_readwrite("floor_height", &Settings::floor_height,
                     "metres (-10..10): the play area's floor is y = floor_height (0 = a floor-level tracking origin)")
      .def_readwrite("foot_lock_follow_seconds", &Settings::foot_lock_follow_seconds,
                     "seconds: a locked foot creeps toward the synthesized one (0 = held still)")
      .def_readwrite("ik_blend_min", &Settings::ik_blend_min, "share of the IK body at close matches (0..1)")
      .def_readwrite("ik_blend_max", &Settings::ik_blend_max, "share of the IK body at far matches (0..1); 0 = off")
      .def_readwrite("ik_blend_near", &Settings::ik_blend_near, "match distance (typical distances) where the rise starts")
      .def_readwrite("ik_blend_far", &Settings::ik_blend_far, "match distance (typical distances) where it ends")
      .def_readwrite("ik_blend_seconds", &Settings::ik_blend_seconds, "smoothing of the match distance, seconds");
  pb::enum_<MatchStatus>(m, "MatchStatus")
      .value("Matched", MatchStatus::Matched)
      .value("Partial", MatchStatus::Partial)
      .value("Unmatched", MatchStatus::Unmatched)
      .value("TrackingLost", MatchStatus::TrackingLost)
      .value("Rejected", MatchStatus::Rejected);
  def_fields(pb::class_<Info>(m, "Info", "Per-frame diagnostics of update().")
      .def(pb::init<>())
      .def_readonly("match", &Info::match)
      .def_readonly("match_weight", &Info::match_weight, "global match weight (0..1)")
      .def_readonly("fallback", &Info::fallback, "share of the direct mapping (0..1)")
      .def_readonly("matches", &Info::matches, "matches per hand [left, right]")
      .def_readonly("best_distance", &Info::best_distance, "best distance per hand, typical-distance units")
      .def_readonly("contact", &Info::contact, "blended foot contact of the candidates [left, right] (0..1)")
      .def_readonly("foot_locked", &Info::foot_locked, "whether each foot is locked [left, right]")
      .def_readonly("ik_share", &Info::ik_share, "share of the IK body in the output (0..1)")
      .def_readonly("active_class", &Info::active_class, "recognised class (index into Database.classes), -1 = not recognising")
      .def_readonly("classes_searched", &Info::classes_searched,
                    "classes this frame's search covered (the recognised one plus the others searched at other_class_cost)")
      .def_readonly("searched", &Info::searched,
                    "whether this frame searched the database (False: its matches were continued, search_interval)"));
}

pb::dict run_dict(AccentRun run) {
  const auto n = static_cast<pb::ssize_t>(run.info.size());
  pb::array_t<int> status(n), match(n);
  Array weight = new_array({n}), contact = new_array({n, 2}), ik_share = new_array({n});
  pb::array_t<bool> locked({n, static_cast<pb::ssize_t>(2)});
  for (pb::ssize_t i = 0; i < n; ++i) {
    const Info& info = run.info[static_cast<std::size_t>(i)];
    status.mutable_data()[i] = static_cast<int>(run.status[static_cast<std::size_t>(i)]);
    match.mutable_data()[i] = static_cast<int>(info.match);
    weight.mutable_data()[i] = info.match_weight;
    ik_share.mutable_data()[i] = info.ik_share;
    for (std::size_t f = 0; f < 2; ++f) {
      contact.mutable_data()[2 * i + static_cast<pb::ssize_t>(f)] = info.contact[f];
      locked.mutable_data()[2 * i + static_cast<pb::ssize_t>(f)] = info.foot_locked[f];
    }
  }
  return pb::dict("motion"_a = std::move(run.output), "status"_a = status, "match"_a = match, "match_weight"_a = weight,
                  "contact"_a = contact, "foot_locked"_a = locked, "ik_share"_a = ik_share, "seconds"_a = run.seconds);
}

pb::dict accentuate_arrays(const Database& db, const pb::handle& head_position, const pb::handle& head_rotation,
                           const pb::handle& left_hand, const pb::handle& right_hand, double fps, const Settings& settings) {
  const auto frames = frames_from_arrays(fps, head_position, head_rotation, left_hand, right_hand, pb::none(), pb::none(), 0.0);
  const Model model = make_model(db, settings);
  AccentRun run;
  {
    pb::gil_scoped_release release;
    run = accentuate(model, frames, fps);
  }
  return run_dict(std::move(run));
}

void bind_runtime(pb::module_& m) {
  auto [model, state] = def_model_state<Model, State>(
      m, &reset, "Immutable accentuation model (database + settings; skeleton scaled to the user); keeps its database alive.",
      "One avatar's memory between frames.");
  model.def_property_readonly("scale", &Model::scale, "user height / database height");
  state.def_property_readonly("bytes", &State::bytes);
  m.def("make_model", &make_model, "db"_a, "settings"_a = Settings{}, pb::keep_alive<0, 1>(),
        "Model from a database and settings; legwork.Error for an unknown class (listing the database's), k out of\n"
        "range, a non-positive exaggeration or height.");
  def_update(m, &update,
             "One frame: head and hands of `frame` in, `out` (a legwork.core.Pose of model.skeleton()) written; returns\n"
             "legwork.core.UpdateStatus. Rejected frames leave state and out untouched.");
  m.def("accentuate", &accentuate_arrays, "db"_a, "head_position"_a, "head_rotation"_a, "left_hand"_a, "right_hand"_a, "fps"_a,
        "settings"_a = Settings{},
        "Whole clip: head_position (frames, 3) metres, head_rotation (frames, 4) w,x,y,z, left_hand/right_hand\n"
        "(frames, 3) metres (wrists) at `fps` Hz (time = frame / fps; NaN rows = lost tracking). Returns a dict:\n"
        "motion (legwork.core.Motion on the model's skeleton, one frame per input frame), status (int32 (frames,)\n"
        "UpdateStatus values), match (int32 (frames,) MatchStatus values), match_weight (float64 (frames,)),\n"
        "contact (float64 (frames, 2): the blended candidates' foot contact, left, right), foot_locked (bool\n"
        "(frames, 2)), ik_share (float64 (frames,): the IK body's share), seconds (time in update()).");
  m.def(
      "accentuate_motion", [](const Database& db, const Settings& s, const Motion& input) { return run_dict(accentuate_motion(db, s, input)); },
      "db"_a, "settings"_a, "input"_a,
      "Whole clip from a motion's head and hands, resampled to the database rate; settings.user_height 0 = the\n"
      "motion's standing height. Returns the same dict as accentuate().");
}

}  // namespace accent_binding
}  // namespace

void bind_accent(pb::module_& m) {
  using namespace accent_binding;  // its helpers and the module names they use
  bind_database(m);
  bind_settings(m);
  bind_runtime(m);
}

}  // namespace legwork::py
