#pragma once
// The walking-in-place tool (`legwork wip`, `legwork wip eval`) as library
// calls: every option in one struct, the run (tracker input -> legs, CSV,
// phase plot, key-frame baseline) and the evaluation over a folder of walking
// trials. Prints its figures and the files it writes to stdout (progress to
// stderr) as the command line does; throws legwork::Error naming the option.
#include <legwork/wip/offline/input.hpp>
#include <legwork/wip/wip.hpp>

#include <string>

namespace legwork::eval {

// Everything `legwork wip` / `legwork wip eval` is asked for.
struct WipJob {
  std::string input, avatar, out, csv, plot, baseline, clip, tracker_out, strip;
  bool synthetic = false, keep_first = false, no_adaptive = false, raw_height = false;
  std::string calibrate = "auto", speed_model = "step";
  std::string mapping = "document", table;  // depth mapping; the learned table file ("" = data/wip/learned_mapping.txt)
  std::string exclude_subjects;             // wip learn: comma-separated CMU subjects left out
  double rate = 30, cutoff = 4, h1 = 0.1, v1 = 0.2, v2 = 0.6, stop_time = 1.5, max_speed = 3.5, step_length = 0.6;
  double speed_gain = 0;  // 0 = the detector's calibrated gain (wip::step_speed_gain)
  // Step detector (wip::GaitSettings / SignalSettings; defaults from there).
  std::string detector = wip::GaitSettings{}.detector == wip::StepDetector::Adaptive ? "adaptive" : "document";
  double detect_cutoff = wip::SignalSettings{}.detect_cutoff, baseline_tau = wip::SignalSettings{}.baseline_tau;
  double noise_factor = wip::GaitSettings{}.noise_factor, lift_fraction = wip::GaitSettings{}.lift_fraction;
  double rise_fraction = wip::GaitSettings{}.rise_fraction, min_lift = wip::GaitSettings{}.min_lift;
  double min_rise = wip::GaitSettings{}.min_rise, rise_noise_factor = wip::GaitSettings{}.rise_noise_factor;
  double rest_time = wip::GaitSettings{}.rest_time, rest_lift = wip::GaitSettings{}.rest_lift;
  double rest_rise = wip::GaitSettings{}.rest_rise, rest_noise_factor = wip::GaitSettings{}.rest_noise_factor;
  double settle_time = wip::GaitSettings{}.settle_time;
  double min_swing_time = wip::GaitSettings{}.min_swing_time;
  wip::SyntheticOptions syn;
  std::string data, eval_out, truth = "learned";  // eval
  double noise = 0.015, drop_rate = 0.02;
  unsigned long long seed = 1;
  int limit = 0;
  bool cross_validate_detector = false;  // eval: also choose the adaptive detector's parameters by subject
};

// The method's settings from the job's options at tracker rate `rate` (Hz).
wip::Settings wip_settings(const WipJob& job, double rate);
void run_wip_job(const WipJob& job);
void run_wip_eval_job(const WipJob& job);
// `legwork wip learn`: the learned depth mapping from the walking trials in
// job.data (default the shared CMU walks), written to job.out.
void run_wip_learn_job(const WipJob& job);
// `legwork wip tune`: the adaptive detector's parameters by cross-validation
// by subject over job.data (report.md, report.json in job.eval_out).
void run_wip_tune_job(const WipJob& job);
// The learned table for job.mapping == "learned": job.table, or the
// repository's data/wip/learned_mapping.txt. Throws naming --table.
wip::LearnedMapping load_learned_table(const WipJob& job);

}  // namespace legwork::eval
