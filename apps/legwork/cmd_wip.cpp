// legwork wip / wip eval: walking-in-place legs from tracked ankle heights,
// and their evaluation on real walking. Options here; the work is in
// legwork::wip (runtime), legwork::wip_offline and legwork::eval (eval/wip.hpp).
#include "command.hpp"

#include <legwork/eval/wip.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/data_files.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>
#include <legwork/io/tracker_csv.hpp>
#include <legwork/wip/offline/input.hpp>
#include <legwork/wip/offline/run.hpp>
#include <legwork/wip/offline/walk_cycle.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

namespace legwork::cli {
namespace {

namespace fs = std::filesystem;
using namespace legwork::wip;

Motion load_bvh_motion(const std::string& path, bool keep_first) {
  io::BvhReadOptions opt;
  opt.drop_first_frame = !keep_first;
  auto f = io::read_bvh(path, opt);
  for (const auto& w : f.report.warnings) std::cerr << "legwork: " << path << ": " << w << "\n";
  return std::move(f.motion);
}

struct WipArgs {
  std::string input, avatar, out, csv, plot, baseline, clip, tracker_out, strip;
  bool synthetic = false, keep_first = false, no_adaptive = false, raw_height = false;
  std::string calibrate = "auto", speed_model = "step";
  double rate = 30, cutoff = 4, h1 = 0.1, v1 = 0.2, v2 = 0.6, stop_time = 1.5, max_speed = 3.5, step_length = 0.6;
  SyntheticOptions syn;
  std::string data, eval_out, truth = "learned";  // eval
  double noise = 0.015, drop_rate = 0.02;
  unsigned long long seed = 1;
  int limit = 0;
};

Settings settings_from(const WipArgs& a, double rate) {
  Settings p;
  p.signal.rate = rate;
  p.signal.cutoff = a.cutoff;
  p.gait.h1 = a.h1;
  p.gait.v1 = a.v1;
  p.gait.v2 = a.v2;
  p.gait.adaptive = !a.no_adaptive;
  p.mapping.normalise_height = !a.raw_height;
  p.mapping.stop_time = a.stop_time;
  p.mapping.max_speed = a.max_speed;
  p.mapping.step_length = a.step_length;
  if (a.speed_model == "step") p.mapping.speed_model = SpeedModel::StepSpeed;
  else if (a.speed_model == "frequency") p.mapping.speed_model = SpeedModel::StepFrequency;
  else throw Error("--speed-model '" + a.speed_model + "': expected 'step' (Bruno et al.) or 'frequency' (GUD-WIP)");
  if (!(rate > 0) || !(a.cutoff > 0) || a.cutoff >= rate / 2)
    throw Error("--cutoff " + std::to_string(a.cutoff) + " Hz must be between 0 and half the sample rate (" +
                std::to_string(rate) + " Hz)");
  return p;
}

TrackerInput load_input(const WipArgs& a) {
  if (a.synthetic == !a.input.empty()) throw Error("give exactly one of --input FILE (.csv or .bvh) and --synthetic");
  if (a.synthetic) {
    SyntheticOptions o = a.syn;
    o.rate = a.rate;
    return tracker_input_synthetic(o);
  }
  const std::string ext = io::extension_of(a.input);
  if (ext == ".csv") return tracker_input_from_csv(a.input);
  if (ext == ".bvh") return tracker_input_from_motion(load_bvh_motion(a.input, a.keep_first), a.input, a.rate);
  throw Error("--input '" + a.input + "' must be a tracker .csv or a .bvh motion");
}

void check_run_options(const WipArgs& a) {
  if (a.out.empty()) throw Error("--out FILE (.glb or .bvh) is required");
  const std::string ext = io::extension_of(a.out);
  if (ext != ".glb" && ext != ".bvh") throw Error("--out '" + a.out + "' must end in .glb or .bvh");
  if (!a.baseline.empty() && a.baseline != "keyframe") throw Error("--baseline '" + a.baseline + "': the only baseline is 'keyframe'");
  if (a.calibrate != "on" && a.calibrate != "off" && a.calibrate != "auto")
    throw Error("--calibrate '" + a.calibrate + "': expected auto, on or off");
  if (!a.plot.empty() && io::extension_of(a.plot) != ".png") throw Error("--plot '" + a.plot + "' must end in .png");
}

void run_wip_command(const WipArgs& a) {
  check_run_options(a);
  const std::string avatar_path = a.avatar.empty() ? io::sample_walk_file("--avatar") : a.avatar;
  const Motion avatar_file = load_bvh_motion(avatar_path, a.keep_first);
  const TrackerInput in = load_input(a);
  const Settings settings = settings_from(a, in.rate);
  const Model model = [&] {
    try {
      return make_model(avatar_file.skeleton, settings);
    } catch (const Error& e) {
      throw Error("--avatar " + avatar_path + ": " + e.what());
    }
  }();
  std::cerr << "legwork wip: " << in.what << "\n";
  std::fprintf(stderr, "legwork wip: avatar %s, leg %.3f m, step length S %.3f m\n", avatar_path.c_str(),
               model.leg_length(), model.shape().S);
  RunOptions ro;
  ro.calibrate = a.calibrate == "on" || (a.calibrate == "auto" && in.still_start);
  Run run;
  try {
    run = run_wip(model, in.frames, ro);
  } catch (const Error& e) {
    throw Error(std::string(e.what()) + " [--calibrate off uses a rolling floor instead]");
  }
  if (run.frames.empty()) throw Error("--input: no tracker frame had a usable time");
  std::cerr << "legwork wip: " << (ro.calibrate ? run.calibration.message : "no calibration: rolling floor estimate") << "\n";
  Motion out = run.motion;
  BaselineRun base;
  if (!a.baseline.empty() || !a.plot.empty()) {
    const std::string clip_path = a.clip.empty() ? io::sample_walk_file("--clip") : a.clip;
    const Motion cycle = extract_walk_cycle(load_bvh_motion(clip_path, false));
    try {
      base = run_keyframe_baseline(model, cycle, run.frames, in.rate, a.baseline.empty() ? nullptr : &out);
    } catch (const Error& e) {
      throw Error("--baseline keyframe: clip " + clip_path + ": " + e.what() + "; pass --clip with a BVH on the avatar's skeleton");
    }
    if (!a.baseline.empty()) std::cerr << "legwork wip: output is the key-frame baseline (clip " << clip_path << ")\n";
  }
  if (io::extension_of(a.out) == ".glb") {
    io::GltfOptions g;
    g.animation_name = a.baseline.empty() ? "walking_in_place" : "keyframe_baseline";
    io::write_glb(a.out, out, g);
  } else {
    io::write_bvh(a.out, out);
  }
  std::printf("%s", eval::describe_wip_run(run.frames, in.rate, in.truth).c_str());
  announce(a.baseline.empty() ? "legs" : "key-frame baseline", a.out);
  if (!a.csv.empty()) io::write_text_file(a.csv, format_info_csv(run.frames)), announce("frames", a.csv);
  if (!a.tracker_out.empty())
    io::write_tracker_csv(a.tracker_out, io::table_from_frames(in.frames)), announce("tracker input", a.tracker_out);
  if (!a.plot.empty()) {
    eval::plot_wip_phases(a.plot, "walking in place: " + in.what, run.frames, run.motion,
                          eval::strip_frames(a.strip, run.frames), base.z, settings.gait);
    announce("phase plot", a.plot);
  }
}

void run_eval_command(const WipArgs& a) {
  if (a.eval_out.empty()) throw Error("--out DIR is required");
  eval::WipEvalRun run;
  const fs::path data = a.data.empty() ? io::walking_data(&run.note) : fs::path(a.data);
  if (!fs::is_directory(data)) throw Error("--data '" + data.string() + "' is not a directory");
  if (fs::exists(a.eval_out) && !fs::is_directory(a.eval_out)) throw Error("--out '" + a.eval_out + "' is not a folder");
  if (!run.note.empty()) std::cerr << "legwork wip eval: note: " << run.note << "\n";
  for (const auto& e : fs::directory_iterator(data))
    if (io::extension_of(e.path().string()) == ".bvh") run.files.push_back(e.path().string());
  std::sort(run.files.begin(), run.files.end());
  if (a.limit > 0 && static_cast<int>(run.files.size()) > a.limit) run.files.resize(static_cast<std::size_t>(a.limit));
  if (run.files.empty()) throw Error("--data '" + data.string() + "' holds no .bvh files");
  run.data = data.string();
  run.clip = a.clip.empty() ? io::sample_walk_file("--clip") : a.clip;
  run.out = a.eval_out;
  run.options.settings = settings_from(a, a.rate);
  run.options.noise = a.noise;
  run.options.drop_rate = a.drop_rate;
  run.options.seed = a.seed;
  run.options.truth.learned = a.truth == "learned";
  run.log = [](const std::string& s) { std::cerr << s << std::flush; };
  const auto s = eval::run_wip_evaluation(run);
  std::printf("%d trials, strict foot-offs +-200 ms: %s\nnoisy F1 %.3f; lenient overlap F1 %.3f (secondary); depth r %.3f / "
              "RMS %.1f cm\n",
              s.trials, eval::format_strict(s.strict).c_str(), s.strict_noisy.f1, s.steps.f1, s.depth.correlation,
              100 * s.depth.rms);
  for (const auto& f : s.written) announce("report", f);
}
void add_method_options(CLI::App* cmd, WipArgs& a) {
  cmd->add_option("--cutoff", a.cutoff, "low-pass cutoff, Hz (default 4)")->check(CLI::PositiveNumber);
  cmd->add_option("--h1", a.h1, "lift height threshold H1, m (default 0.1)")->check(CLI::PositiveNumber);
  cmd->add_option("--v1", a.v1, "rise velocity threshold V1, m/s (default 0.2)")->check(CLI::PositiveNumber);
  cmd->add_option("--v2", a.v2, "descent velocity threshold V2, m/s (default 0.6)")->check(CLI::PositiveNumber);
  cmd->add_flag("--no-adaptive", a.no_adaptive,
                "use H1/V1/V2 as fixed thresholds (default: they shrink toward the user's own step)");
  cmd->add_flag("--raw-height", a.raw_height,
                "feed the raw height into the equations (default: normalised by the user's step apex)");
  cmd->add_option("--stop-time", a.stop_time, "double support longer than this stops the legs, s (default 1.5)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--step-length", a.step_length, "maximum step length S for a 0.8 m leg, m (default 0.6; scaled to the avatar)")
      ->check(CLI::PositiveNumber);
}
// ---- registration ---------------------------------------------------------

void register_wip(CLI::App& app) {
  auto a = std::make_shared<WipArgs>();
  auto* cmd = app.add_subcommand(
      "wip",
      "Walking-in-place legs: tracked ankle heights -> gait phases -> two-bone IK leg animation that walks forward.\n"
      "Input: a tracker CSV (time,left_ankle_x/y/z,right_ankle_x/y/z), a BVH whose ankles act as the tracker, or\n"
      "--synthetic in-place stepping. Output: the avatar's animation (.glb or .bvh), per-frame CSV, phase plot.\n"
      "Example: legwork wip --synthetic --out legs.glb --csv frames.csv --plot phases.png\n"
      "Example: legwork wip --input data/cmu/bvh/walking/07_01.bvh --out legs.bvh --plot phases.png");
  cmd->add_option("--input", a->input, "tracker .csv or .bvh motion (its ankle joints are the tracker)");
  cmd->add_flag("--synthetic", a->synthetic, "generate in-place stepping instead of reading --input");
  cmd->add_option("--avatar", a->avatar, "avatar skeleton .bvh (default data/cmu/bvh/walking/07_01.bvh)");
  cmd->add_option("--out", a->out, "output animation: .glb or .bvh");
  cmd->add_option("--csv", a->csv, "per-frame CSV: phases, heights, velocities, IK targets, speed");
  cmd->add_option("--plot", a->plot, "phase plot .png (heights, velocities, phases, depths + side-view strip)");
  cmd->add_option("--strip", a->strip, "frames for the plot's side-view strip, e.g. 40,45,50 (default: six)");
  cmd->add_option("--baseline", a->baseline, "'keyframe': output the key-frame baseline (canned walk cycle) instead");
  cmd->add_option("--clip", a->clip, "walking BVH for the baseline's walk cycle (default: the default avatar file)");
  cmd->add_option("--tracker-out", a->tracker_out, "also write the (e.g. synthetic) tracker input as CSV");
  cmd->add_option("--rate", a->rate, "tracker rate for --synthetic and BVH input, Hz (default 30)")
      ->check(CLI::Range(10.0, 1000.0));
  cmd->add_option("--calibrate", a->calibrate,
                  "floor calibration from the first 3 s standing still: auto (CSV/synthetic yes, BVH no), on, off");
  cmd->add_option("--speed-model", a->speed_model, "forward speed: step (Bruno et al., default) or frequency (GUD-WIP)");
  cmd->add_option("--max-speed", a->max_speed, "forward speed cap, m/s (default 3.5)")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--keep-first-frame", a->keep_first, "keep BVH frame 0 (dropped by default: CMU's T-pose)");
  add_method_options(cmd, *a);
  auto& s = a->syn;
  cmd->add_option("--duration", s.duration, "synthetic: seconds (default 20)")->check(CLI::PositiveNumber);
  cmd->add_option("--stand-time", s.stand_time, "synthetic: standing still at the start, s (default 3)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--cadence", s.cadence, "synthetic: steps per second (default 1.8)")->check(CLI::PositiveNumber);
  cmd->add_option("--step-height", s.step_height, "synthetic: ankle lift, m (default 0.15)")->check(CLI::PositiveNumber);
  cmd->add_option("--asymmetry", s.asymmetry, "synthetic: right lift = (1 - a) * left (default 0)")->check(CLI::Range(0.0, 0.9));
  cmd->add_option("--noise", s.noise, "synthetic: jitter per coordinate, m (default 0.015)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--drop-rate", s.drop_rate, "synthetic: dropped-sample probability (default 0.02)")->check(CLI::Range(0.0, 0.9));
  cmd->add_option("--pause", s.pause_start, "synthetic: a 3 s stop starts here, s (default 11; negative = none)");
  cmd->add_option("--seed", s.seed, "synthetic: random seed (default 1)");

  auto* ev = cmd->add_subcommand(
      "eval",
      "Evaluate on real walking: step detection (precision/recall/F1, latency) against mocap gait events, with and\n"
      "without Kinect-like noise, and IK-target depth vs the real feet (correlation, RMS), also for the key-frame\n"
      "baseline. Writes report.md, report.json, summary.png and one PNG per trial.\n"
      "Example: legwork wip eval --data ../shared/data/cmu/bvh/walking --out wip-eval");
  ev->add_option("--data", a->data, "folder of walking BVH trials (default ../shared/data/cmu/bvh/walking, else data/cmu/bvh/walking)");
  ev->add_option("--out", a->eval_out, "output folder")->required();
  ev->add_option("--clip", a->clip, "walking BVH for the baseline's walk cycle (default data/cmu/bvh/walking/07_01.bvh)");
  ev->add_option("--noise", a->noise, "jitter of the noisy run, m (default 0.015)")->check(CLI::NonNegativeNumber);
  ev->add_option("--drop-rate", a->drop_rate, "dropped samples in the noisy run (default 0.02)")->check(CLI::Range(0.0, 0.9));
  ev->add_option("--seed", a->seed, "noise seed (default 1)");
  ev->add_option("--truth", a->truth, "ground-truth contacts: learned (per-foot stance height, default) or fixed (the former "
                                      "3 cm over a rolling floor)")
      ->check(CLI::IsMember({"learned", "fixed"}));
  ev->add_option("--limit", a->limit, "evaluate only the first N trials")->check(CLI::PositiveNumber);
  ev->add_option("--rate", a->rate, "tracker rate, Hz (default 30)")->check(CLI::Range(10.0, 1000.0));
  add_method_options(ev, *a);
  ev->callback([a] { run_eval_command(*a); });
  cmd->callback([a, ev] {
    if (ev->parsed()) return;
    if (a->syn.pause_start < 0) a->syn.pause_length = 0;
    run_wip_command(*a);
  });
}

LEGWORK_COMMAND(register_wip, 30);

}  // namespace
}  // namespace legwork::cli
