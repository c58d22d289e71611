#include <legwork/eval/accent_job.hpp>

#include <legwork/accent/offline/retarget.hpp>
#include <legwork/accent/offline/run.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/eval/run.hpp>
#include <legwork/eval/session.hpp>
#include <legwork/io/text.hpp>
#include <legwork/io/tracker_csv.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace legwork::eval {

using namespace legwork::accent;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

SearchMode parse_search_mode(const std::string& m) {
  if (m == "fast") return SearchMode::Fast;
  if (m == "exact") return SearchMode::Exact;
  if (m == "brute") return SearchMode::BruteForce;
  throw Error("--mode '" + m + "': expected fast, exact or brute");
}
namespace {
const char* mode_name(SearchMode m) { return m == SearchMode::Fast ? "fast" : m == SearchMode::Exact ? "exact" : "brute"; }

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Settings::recognize_class: frames per recognised class and the switches
// between them (empty when the run did not recognise classes).
json recognized_classes(const AccentRun& run, const Database& db) {
  json frames = json::object();
  int switches = 0, last = -1;
  for (const auto& info : run.info) {
    if (info.active_class < 0) continue;
    const std::string& name = db.classes()[static_cast<std::size_t>(info.active_class)];
    frames[name] = frames.value(name, 0) + 1;
    switches += last >= 0 && info.active_class != last;
    last = info.active_class;
  }
  if (frames.empty()) return json::object();
  return {{"frames", frames}, {"switches", switches}};
}

// `legwork accent run` makes its run in memory (input frames, the accentuated
// motion, per-frame figures: about 5 KB a frame), so a run is refused above
// this many frames before the database is searched: 69 minutes at 120 Hz.
// (The runtime itself, accent::update, keeps no history.)
constexpr double kMaxRunFrames = 500'000;

void check_run_frames(double frames, const std::string& input, double fps) {
  if (frames <= kMaxRunFrames) return;
  char buf[400];
  std::snprintf(buf, sizeof buf, "--input '%s' makes %.0f frames at the database's %g Hz; the limit is %.0f frames (a run is made in memory)",
                input.c_str(), std::min(frames, 1e18), fps, kMaxRunFrames);
  throw Error(buf);
}

}  // namespace

void run_accent_job(const AccentJob& a) {
  io::require_extension("--out", a.out, {".glb", ".bvh"});
  if (!a.video.empty()) io::require_extension("--video", a.video, {".mp4"});
  const auto t0 = Clock::now();
  const Database db = load_database(a.db);
  const double load_s = seconds_since(t0);
  Settings cfg;
  cfg.search = parse_search_mode(a.mode);
  cfg.k_left = a.k_left >= 0 ? a.k_left : a.k;
  cfg.k_right = a.k_right >= 0 ? a.k_right : a.k;
  cfg.threshold = a.threshold;
  cfg.align = !a.no_align;
  cfg.smooth = !a.no_smooth;
  cfg.smooth_halflife = a.smooth_halflife;
  cfg.smooth_feedforward = a.smooth_feedforward;
  cfg.lying_root_smoothing = a.lying_root_smoothing;
  cfg.lying_crown = a.lying_crown;
  cfg.other_class_cost = a.other_class_cost;
  cfg.search_interval = a.search_interval;
  cfg.joint_limits = !a.no_limits;
  cfg.exaggeration = a.exaggerate;
  cfg.classes = io::split_commas(a.classes);
  cfg.hand_ik = a.hand_ik;
  cfg.max_head_tilt_deg = a.max_tilt;
  cfg.recognize_class = !a.no_class_recognition;
  cfg.class_hold_seconds = a.class_hold;
  cfg.class_margin = a.class_margin;
  cfg.foot_lift_height = a.foot_lift_height;
  cfg.foot_lock_slack = a.foot_lock_slack;
  cfg.foot_lock_hold_seconds = a.foot_lock_hold;
  cfg.foot_swing_speed = a.foot_swing_speed;
  cfg.travel_weight = a.travel_weight;
  cfg.max_head_height_diff = a.max_head_height_diff;
  cfg.floor = !a.no_floor;
  cfg.floor_height = a.floor_height;
  const double fps = db.feature_space().fps;
  std::vector<TrackerFrame> frames;
  Motion truth;
  const auto in_ext = io::extension_of(a.input);
  if (in_ext == ".bvh") {
    Motion file = io::read_motion(a.input, a.input_options).motion;
    check_run_frames(std::floor(file.duration() * fps) + 1, a.input, fps);
    truth = resample(file, fps);
    frames = tracker_frames_from_motion(truth);
    cfg.user_height = a.height > 0 ? a.height : measure_body(truth.skeleton).standing_height;
  } else if (in_ext == ".csv") {
    frames = io::frames_from_table(io::read_tracker_csv(a.input), a.input,
                                   {Device::Head, Device::LeftHand, Device::RightHand});
    cfg.user_height = a.height;
  } else {
    throw Error("--input '" + a.input + "' must be a .bvh trial or a .csv headset session");
  }
  if (frames.empty()) throw Error("--input '" + a.input + "' has no samples");
  check_run_frames(static_cast<double>(frames.size()), a.input, fps);
  if (!a.save_session.empty()) {
    io::write_tracker_csv(a.save_session, io::table_from_frames(frames));
    io::announce("headset session", a.save_session);
  }
  AccentRun run = accentuate(make_model(db, cfg), frames, fps);
  for (const auto& w : run.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  const SessionFigures fig = session_figures(run);
  std::printf("database: %s (%d windows, loaded in %.1f ms)\n", a.db.c_str(), db.window_count(), load_s * 1e3);
  std::printf("frames: %d at %.4g Hz; %.0f frames/s in update() (%s search); mean match weight %.2f\n", run.output.frame_count(), fps,
              fig.frames_per_second, mode_name(cfg.search), fig.mean_match_weight);
  for (const auto& [s, n] : fig.statuses) std::printf("  %-14s %d frames\n", s.c_str(), n);
  const json recognized = recognized_classes(run, db);
  if (!recognized.empty()) std::printf("recognised classes: %s\n", recognized.dump().c_str());
  Motion result = run.output;
  if (!a.target.empty()) {
    Motion tgt = io::load_bvh(a.target, io::BvhReadOptions{});
    require_roles(tgt.skeleton, a.target);
    tgt.skeleton.scale(cfg.user_height > 0 ? cfg.user_height / std::max(measure_body(tgt.skeleton).standing_height, 1e-6) : 1.0);
    result = retarget_motion_at_head(run.output, tgt.skeleton);
  }
  io::write_motion(a.out, result, "motion", "--out");
  io::announce("accentuated motion", a.out);
  Motion ik;
  // The IK baseline gets what the engine gets (as in `eval accent`): the database's skeleton at the
  // user's height, never the input's own bone lengths.
  if (a.compare_ik) ik = run_ik_baseline(run.output.skeleton, frames, fps);
  json j;
  j["input"] = a.input;
  j["database"] = a.db;
  j["frames"] = run.output.frame_count();
  j["fps"] = fps;
  j["frames_per_second"] = fig.frames_per_second;
  j["load_ms"] = load_s * 1e3;
  j["statuses"] = fig.statuses;
  if (a.compare_ik) j["ik_skeleton"] = "database skeleton at the user's height";
  if (!recognized.empty()) j["recognized_classes"] = recognized;
  if (!truth.skeleton.names.empty()) {
    std::printf("vs ground truth:\n");
    j["accent_error"] = truth_error(run.output, truth);
    std::printf("%s", describe_truth_error("accent", j["accent_error"]).c_str());
    if (a.compare_ik) {
      j["ik_error"] = truth_error(ik, truth);
      std::printf("%s", describe_truth_error("IK baseline", j["ik_error"]).c_str());
    }
  }
  if (!a.json_path.empty()) {
    j["per_frame"] = session_per_frame(run);
    io::write_text_file(a.json_path, j.dump(1) + "\n");
    io::announce("run report", a.json_path);
  }
  if (!a.video.empty()) {
    render_session_video(frames, fps, run.output, a.compare_ik ? &ik : nullptr,
                               truth.skeleton.names.empty() ? nullptr : &truth,
                               "legwork accent: " + std::filesystem::path(a.input).filename().string(), a.video);
    io::announce("video", a.video);
  }
}

}  // namespace legwork::eval
