// legwork wip / wip eval: walking-in-place legs from tracked ankle heights,
// and their evaluation on real walking. Options here; the work is in
// legwork::wip (runtime), legwork::wip_offline and legwork::eval (eval/wip.hpp).
#include "command.hpp"

#include <legwork/eval/wip_job.hpp>

#include <memory>

namespace legwork::cli {
namespace {


// The Kinect-like noise of the evaluation's noisy run (wip eval, wip tune).
void add_noise_options(CLI::App* cmd, eval::WipJob& a) {
  cmd->add_option("--noise", a.noise, "jitter of the noisy run, m (default 0.015)")->check(CLI::Range(0.0, 0.2));
  cmd->add_option("--drop-rate", a.drop_rate, "dropped samples in the noisy run (default 0.02)")->check(CLI::Range(0.0, 0.9));
  cmd->add_option("--seed", a.seed, "noise seed (default 1)");
}

void add_method_options(CLI::App* cmd, eval::WipJob& a) {
  cmd->add_option("--cutoff", a.cutoff, "low-pass cutoff, Hz (default 4)")->check(positive_up_to(50));
  cmd->add_option("--h1", a.h1, "lift height threshold H1, m (default 0.1)")->check(positive_up_to(1));
  cmd->add_option("--v1", a.v1, "rise velocity threshold V1, m/s (default 0.2)")->check(positive_up_to(5));
  cmd->add_option("--v2", a.v2, "descent velocity threshold V2, m/s (default 0.6)")->check(positive_up_to(10));
  cmd->add_flag("--no-adaptive", a.no_adaptive,
                "use H1/V1/V2 as fixed thresholds (default: they shrink toward the user's own step)");
  cmd->add_option("--detector", a.detector,
                  "foot-off detection: document (H1/V1/V2 on the 4 Hz height) or adaptive (lighter filter, stance baseline, "
                  "noise-scaled thresholds; default " + a.detector + ")")
      ->check(CLI::IsMember({"document", "adaptive"}));
  cmd->add_option("--detect-cutoff", a.detect_cutoff, "adaptive detector: low-pass of its signal, Hz")->check(positive_up_to(50));
  cmd->add_option("--baseline-tau", a.baseline_tau, "adaptive detector: stance baseline time constant, s")
      ->check(positive_up_to(60));
  cmd->add_option("--noise-factor", a.noise_factor, "adaptive detector: foot-off height >= this x the tracker jitter")
      ->check(CLI::Range(0.0, 20.0));
  cmd->add_option("--rise-noise-factor", a.rise_noise_factor,
                  "adaptive detector: foot-off speed >= this (1/s) x the tracker jitter")
      ->check(CLI::Range(0.0, 200.0));
  cmd->add_option("--lift-fraction", a.lift_fraction, "adaptive detector: foot-off height >= this x the apex estimate")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--rise-fraction", a.rise_fraction, "adaptive detector: foot-off speed >= this x the peak rise estimate")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--min-lift", a.min_lift, "adaptive detector: lowest foot-off height, m")->check(CLI::Range(0.0, 0.1));
  cmd->add_option("--min-rise", a.min_rise, "adaptive detector: lowest foot-off speed, m/s")->check(CLI::Range(0.0, 2.0));
  cmd->add_option("--rest-time", a.rest_time,
                  "adaptive detector: both feet down this long (s) -> start-step thresholds (default 0.5; 0 = off)")
      ->check(CLI::Range(0.0, 60.0));
  cmd->add_option("--rest-lift", a.rest_lift, "adaptive detector: start steps' lowest foot-off height, m (default 0.02)")
      ->check(CLI::Range(0.0, 0.1));
  cmd->add_option("--rest-rise", a.rest_rise, "adaptive detector: start steps' lowest foot-off speed, m/s (default 0.1)")
      ->check(CLI::Range(0.0, 2.0));
  cmd->add_option("--rest-noise-factor", a.rest_noise_factor,
                  "adaptive detector: start steps' foot-off height >= this x the tracker jitter (default 3.5)")
      ->check(CLI::Range(0.0, 20.0));
  cmd->add_option("--settle-time", a.settle_time,
                  "adaptive detector: a terminal swing steady this long (s) has landed (default 0.3; 0 = off)")
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_option("--min-swing-time", a.min_swing_time,
                  "adaptive detector: no landing before this long (s) after a foot-off (default 0.1; 0 = off)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_flag("--raw-height", a.raw_height,
                "feed the raw height into the equations (default: normalised by the user's step apex)");
  cmd->add_option("--stop-time", a.stop_time, "double support longer than this stops the legs, s (default 1.5)")
      ->check(positive_up_to(60));
  cmd->add_option("--mapping", a.mapping,
                  "fore-aft IK-target depths: document (equations 1-4, default) or learned (table from real walks)")
      ->check(CLI::IsMember({"document", "learned"}));
  cmd->add_option("--table", a.table, "learned mapping table (default data/wip/learned_mapping.txt; `legwork wip learn`)");
  cmd->add_option("--step-length", a.step_length, "maximum step length S for a 0.8 m leg, m (default 0.6; scaled to the avatar)")
      ->check(positive_up_to(2));
}
// ---- registration ---------------------------------------------------------

void register_wip(CLI::App& app) {
  auto a = std::make_shared<eval::WipJob>();
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
  output_file(cmd->add_option("--out", a->out, "output animation: .glb or .bvh"));
  output_file(cmd->add_option("--csv", a->csv, "per-frame CSV: phases, heights, velocities, IK targets, speed"));
  output_file(cmd->add_option("--plot", a->plot, "phase plot .png (heights, velocities, phases, depths + side-view strip)"));
  cmd->add_option("--strip", a->strip, "frames for the plot's side-view strip, e.g. 40,45,50 (default: six)");
  cmd->add_option("--baseline", a->baseline, "'keyframe': output the key-frame baseline (canned walk cycle) instead");
  cmd->add_option("--clip", a->clip, "walking BVH for the baseline's walk cycle (default: the default avatar file)");
  output_file(cmd->add_option("--tracker-out", a->tracker_out, "also write the (e.g. synthetic) tracker input as CSV"));
  cmd->add_option("--rate", a->rate, "tracker rate for --synthetic and BVH input, Hz (default 30)")
      ->check(CLI::Range(10.0, 1000.0));
  cmd->add_option("--calibrate", a->calibrate,
                  "floor calibration from the first 3 s standing still: auto (CSV/synthetic yes, BVH no), on, off");
  cmd->add_option("--speed-model", a->speed_model, "forward speed: step (Bruno et al., default) or frequency (GUD-WIP)");
  cmd->add_option("--max-speed", a->max_speed, "forward speed cap, m/s (default 3.5)")->check(CLI::Range(0.0, 12.0));
  cmd->add_option("--speed-gain", a->speed_gain,
                  "step-speed model gain (m/s per m/s of mean vertical foot speed); 0 = the detector's calibrated gain "
                  "(document 2.15, adaptive 4.61)")
      ->check(CLI::Range(0.0, 20.0));
  cmd->add_flag("--keep-first-frame", a->keep_first, "keep BVH frame 0 (dropped by default: CMU's T-pose)");
  add_method_options(cmd, *a);
  auto& s = a->syn;
  cmd->add_option("--duration", s.duration, "synthetic: seconds (default 20)")->check(positive_up_to(1000000));
  cmd->add_option("--stand-time", s.stand_time, "synthetic: standing still at the start, s (default 3)")
      ->check(CLI::Range(0.0, 600.0));
  cmd->add_option("--cadence", s.cadence, "synthetic: steps per second (default 1.8)")->check(positive_up_to(10));
  cmd->add_option("--step-height", s.step_height, "synthetic: ankle lift, m (default 0.15)")->check(positive_up_to(1));
  cmd->add_option("--asymmetry", s.asymmetry, "synthetic: right lift = (1 - a) * left (default 0)")->check(CLI::Range(0.0, 0.9));
  cmd->add_option("--noise", s.noise, "synthetic: jitter per coordinate, m (default 0.015)")->check(CLI::Range(0.0, 0.2));
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
  add_noise_options(ev, *a);
  ev->add_option("--truth", a->truth, "ground-truth contacts: learned (per-foot stance height, default) or fixed (the former "
                                      "3 cm over a rolling floor)")
      ->check(CLI::IsMember({"learned", "fixed"}));
  ev->add_option("--limit", a->limit, "evaluate only the first N trials")->check(CLI::Range(1, 1000000));
  ev->add_flag("--cross-validate-detector", a->cross_validate_detector,
               "also choose the adaptive detector's parameters by cross-validation by subject (as `wip tune`) and "
               "report the held-out figures");
  ev->add_option("--rate", a->rate, "tracker rate, Hz (default 30)")->check(CLI::Range(10.0, 1000.0));
  add_method_options(ev, *a);
  ev->callback([a] { eval::run_wip_eval_job(*a); });
  auto* learn = cmd->add_subcommand(
      "learn",
      "Learn the walking-in-place depth mapping from real walks: each trial's own ankles run through the method's\n"
      "filters and gait machines, paired with the real fore-aft ankle offsets; writes the table used by --mapping learned.\n"
      "Example: legwork wip learn --data ../shared/data/cmu/bvh/walking --out data/wip/learned_mapping.txt");
  learn->add_option("--data", a->data, "folder of walking BVH trials (default ../shared/data/cmu/bvh/walking)");
  output_file(learn->add_option("--out", a->out, "the learned table (.txt)")->required());
  learn->add_option("--exclude-subjects", a->exclude_subjects, "CMU subjects left out, e.g. 105,16 (for held-out tests)");
  learn->add_option("--limit", a->limit, "use only the first N trials")->check(CLI::Range(1, 1000000));
  learn->add_option("--rate", a->rate, "tracker rate, Hz (default 30)")->check(CLI::Range(10.0, 1000.0));
  add_method_options(learn, *a);
  learn->callback([a] { eval::run_wip_learn_job(*a); });
  auto* tune = cmd->add_subcommand(
      "tune",
      "Choose the adaptive step detector's parameters by cross-validation by subject: every parameter set of a grid\n"
      "scored (strict F1 clean and with noise, latency, false steps on still segments) on every walking trial; each\n"
      "subject scored with the set chosen on the other subjects. Writes report.md and report.json.\n"
      "Example: legwork wip tune --data ../shared/data/cmu/bvh/walking --out wip-tune");
  tune->add_option("--data", a->data, "folder of walking BVH trials (default ../shared/data/cmu/bvh/walking)");
  tune->add_option("--out", a->eval_out, "output folder")->required();
  tune->add_option("--limit", a->limit, "use only the first N trials")->check(CLI::Range(1, 1000000));
  add_noise_options(tune, *a);
  tune->callback([a] { eval::run_wip_tune_job(*a); });
  cmd->callback([a, ev, learn, tune] {
    if (ev->parsed() || learn->parsed() || tune->parsed()) return;
    if (a->syn.pause_start < 0) a->syn.pause_length = 0;
    eval::run_wip_job(*a);
  });
}

LEGWORK_COMMAND(register_wip, 30);

}  // namespace
}  // namespace legwork::cli
