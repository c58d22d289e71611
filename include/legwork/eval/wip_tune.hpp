#pragma once
// Choosing the adaptive step detector's parameters by cross-validation by
// subject (offline; `legwork wip tune`, and the cross-validated rows of
// `legwork wip eval`). Every grid point runs every trial's own ankles (clean,
// and with Kinect-like noise) through wip::update; for each CMU subject the
// point that scores best on the OTHER subjects' trials is chosen and scored
// on that subject's trials only, so no held-out figure was tuned on itself.
// Allocates, throws legwork::Error.
#include <legwork/eval/wip.hpp>

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace legwork::eval {

// One point of the detector's parameter grid (wip::SignalSettings /
// wip::GaitSettings fields of the adaptive detector).
struct DetectorParams {
  double detect_cutoff = 10, lift_fraction = 0.2, min_lift = 0.01, min_rise = 0.05;
  double noise_factor = 2.5, rise_noise_factor = 20, rise_fraction = 0.2;
  // Start steps after both feet rest (wip::GaitSettings rest_*; rest_time 0 = off) and the steady
  // terminal swing's landing (settle_time, 0 = off).
  double rest_time = 0.5, rest_noise_factor = 3.5, settle_time = 0.3;
  double min_swing_time = 0.1;  // no landing before this long after the foot-off (0 = off)
  void apply(wip::Settings& s) const;  // sets the adaptive detector and these fields
  static DetectorParams of(const wip::Settings& s);
  std::string describe() const;  // "cutoff 8 Hz, lift 0.2 x apex, ..."
};
// The grid searched (2916 points: 243 of the walking thresholds x 4 start-step variants x 3 minimum swing
// times; docs/wip.md).
std::vector<DetectorParams> default_detector_grid();

// A trial prepared once: its true swings, still segments and tracker frames
// (clean and noisy), scored for any detector setting.
struct DetectionTrial {
  std::string name, subject;
  Skeleton skeleton;  // the trial's own skeleton: the avatar
  std::vector<SwingEvent> truth;
  std::vector<StillSegment> still;
  std::vector<TrackerFrame> clean, noisy;
  double t_begin = 0, t_end = 0;
};
DetectionTrial prepare_detection_trial(const Motion& trial, const std::string& name, const WipEvalOptions& opt,
                                       int trial_index);

// Counts of one setting on a set of trials (pooled).
struct DetectionCounts {
  StrictScore strict, strict_100, noisy;
  int false_steps = 0, false_steps_noisy = 0;
  double still_minutes = 0;
  double false_per_minute() const { return still_minutes > 0 ? false_steps / still_minutes : NAN; }
  double false_per_minute_noisy() const { return still_minutes > 0 ? false_steps_noisy / still_minutes : NAN; }
};
DetectionCounts score_detection(const DetectionTrial& t, const wip::Settings& settings);
DetectionCounts pool(std::span<const DetectionCounts> parts);

struct DetectorFold {
  std::string subject;
  int trials = 0;
  int chosen = -1;  // grid index chosen on the other subjects
  DetectionCounts held_out;
};
struct DetectorTuning {
  std::vector<DetectorParams> grid;
  std::vector<DetectionCounts> all;   // each grid point on every trial (in-sample, for reference)
  std::vector<DetectorFold> folds;    // one per subject
  DetectionCounts cross_validated;    // the held-out subjects' counts pooled
  int chosen_all = -1;                // the point chosen on all subjects (the shipped defaults)
  // Selection rule: the highest clean + noisy strict F1 among points with at
  // most `max_false_per_minute` false steps per minute on still segments
  // (clean and noisy) and a median latency <= `max_latency_ms`; without such
  // a point, the highest F1 sum.
  double max_false_per_minute = 1, max_latency_ms = 60;
};
// `settings`: the rest of the method's settings (rate, mapping, ...).
DetectorTuning tune_detector(std::span<const DetectionTrial> trials, const wip::Settings& settings,
                             std::vector<DetectorParams> grid, const std::function<void(int, int)>& progress = {});
// report.md section / JSON of a tuning.
std::string tuning_markdown(const DetectorTuning& t);
std::string tuning_json(const DetectorTuning& t);

}  // namespace legwork::eval
