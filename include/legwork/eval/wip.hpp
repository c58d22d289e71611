#pragma once
// Evaluation of walking in place on real walking (offline): swings detected
// by the gait machines against true gait events from mocap, step-detection
// scores, true foot-forward offsets and curve agreement, the key-frame
// baseline beside it, and the whole `legwork wip eval` report (report.json,
// report.md, summary.png, one PNG per trial). Allocates, throws legwork::Error.
#include <legwork/core/motion.hpp>
#include <legwork/wip/offline/synthetic.hpp>
#include <legwork/core/contacts.hpp>
#include <legwork/wip/offline/learn.hpp>
#include <legwork/eval/wip_speed.hpp>
#include <legwork/wip/wip.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace legwork::eval {

using legwork::SwingEvent;

// Swings seen by the gait machines (foot-off to foot-strike events); a swing
// still open at the last frame ends there, flagged `cut` (its foot-off was detected).
std::vector<SwingEvent> detected_swings(std::span<const wip::Info> frames);

struct StepScore {
  int true_steps = 0, detected = 0, matched = 0;
  double precision = 0, recall = 0, f1 = 0;
  double off_latency_ms = 0;     // mean detected - true foot-off over matched steps
  double strike_latency_ms = 0;  // mean detected - true foot-strike
  std::vector<double> off_latencies_ms;
};
// One-to-one matching of swings of the same foot whose intervals overlap,
// ignoring swings outside [t_begin, t_end] (e.g. the filter's settling time).
StepScore score_steps(std::span<const SwingEvent> detected, std::span<const SwingEvent> truth, double t_begin,
                      double t_end);
// Sums counts; latencies averaged over all matched steps.
StepScore combine(std::span<const StepScore> scores);

// The field's standard step score: detected and true foot-offs of the same
// foot matched one to one when within +-tolerance, closest pairs first
// (greedy by |detected - true|). Only true foot-offs in [t_begin, t_end]
// count; a detection in [t_begin, t_end] with no partner is a false positive.
// Rates are NaN (reported as n/a) when undefined: precision without
// detections, recall without true steps, F1 without either.
struct StrictScore {
  double tolerance_ms = 200;
  int true_steps = 0, detected = 0, matched = 0;
  double precision = NAN, recall = NAN, f1 = NAN;
  std::vector<double> latencies_ms;  // signed, detected - true foot-off, per match
  double median_ms = NAN, p90_ms = NAN, mean_ms = NAN;  // core percentile(): index floor(p (n - 1))
  void finish();  // rates and latency statistics from the counts and latencies
};
StrictScore match_foot_offs(std::span<const SwingEvent> detected, std::span<const SwingEvent> truth, double tolerance,
                            double t_begin, double t_end);
// The detections that match_foot_offs (+-tolerance) leaves without a true
// partner: the false steps, wherever they are.
std::vector<SwingEvent> unmatched_detections(std::span<const SwingEvent> detected, std::span<const SwingEvent> truth,
                                             double tolerance);
StrictScore combine(std::span<const StrictScore> scores);
// A number printed with `printf_format`, or "n/a" when it is not finite.
std::string format_or_na(double v, const char* printf_format);
// "precision 0.950, recall n/a, F1 ..., foot-off latency median 55 ms, p90 90 ms".
std::string format_strict(const StrictScore& s);

// A still stretch of a trial: both feet in contact throughout (ground truth).
struct StillSegment {
  std::string trial;
  double begin = 0, end = 0;  // s
  int false_steps = 0;        // detected foot-offs inside
  int false_steps_noisy = 0;  // the same in the noisy run
};
// Still stretches of at least `min_duration` s within [t_begin, t_end], from
// the true contacts of both feet; false steps counted from `detected` (pass
// the unmatched detections: a detection matched to the true foot-off that
// ends the stretch is an early step, not a false one).
std::vector<StillSegment> still_segments(const Motion& m, const std::string& name, const ContactOptions& truth,
                                         std::span<const SwingEvent> detected, double min_duration, double t_begin,
                                         double t_end);

// True forward offset of each ankle from the pelvis along the walking heading
// (from the hip line, smoothed over +-0.5 s), at `rate` Hz from t = 0.
struct DepthTrack {
  std::vector<double> time;
  std::vector<double> z[2];
  std::vector<Vec3> pelvis;      // world pelvis position per sample (walking speed, wip_speed.hpp)
  double heading_range_deg = 0;  // max - min of the (unwrapped) walking heading over the trial
  // The pelvis's travel per sample (horizontal path over +-kTravelWindow s): speed (m/s), how fast its
  // direction turns (degrees/s, between the windows ending and starting here) and the cosine between the
  // travel direction and the walking heading (1 forward, -1 backward, 0 sideways).
  std::vector<double> travel_speed, travel_turn_deg_s, travel_along;
};

// What the body does at a sample, for the depth error's breakdown by segment
// (report "IK-target depth by segment"): checked in this order, a walking
// frame (the method's flag) whose pelvis travels more than 60 degrees off the
// heading at >= kSlowTravel is Backward (backward or sideways walking: the
// ankle heights cannot show it), a frame the method is not walking is
// NotWalking (before the first step, after the stop rule), a pelvis slower than
// kSlowTravel is Slow (turns on the spot, start and stop shuffles), a travel
// direction turning faster than kTurnRate is Turning, else Straight.
enum class DepthSegment { Straight, Turning, Slow, Backward, NotWalking };
inline constexpr int kDepthSegments = 5;
inline constexpr double kTravelWindow = 0.27;    // s
inline constexpr double kSlowTravel = 0.25;      // m/s
inline constexpr double kTurnRate = 45;          // degrees/s
inline constexpr double kBackwardCosine = 0.5;   // travel more than 60 degrees off the heading
const char* depth_segment_name(DepthSegment s);  // "walking straight", ...
DepthSegment depth_segment(const DepthTrack& d, std::size_t sample, bool walking);
// Trials whose heading spans more than this are "turning" walks in the report.
inline constexpr double kTurningDegrees = 90;
DepthTrack true_depths(const Motion& m, double rate);

struct Agreement {
  double correlation = 0, rms = 0;  // Pearson r; RMS in metres
  int samples = 0;
  // Accumulated sums so several trials can be pooled.
  double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0, se2 = 0;
  void add(double generated, double truth);
  void merge(const Agreement& other);  // pools another set's sums
  void finish();
};

struct WipEvalOptions {
  wip::Settings settings;      // the method's settings (signal.rate = tracker rate)
  ContactOptions truth{.end_swings = true};  // foot-offs of swings the clip's end cuts count too
  double noise = 0.015;        // Kinect-like jitter for the noisy run, m
  double drop_rate = 0.02;     // dropped samples in the noisy run
  std::uint64_t seed = 1;      // noise seed (mixed with the trial index)
  double settle = 0.5;         // s at the start ignored (filter and floor settle)
  double min_still = 1.0;      // s: shortest still segment scored for false steps
};

// One trial driven through the method with its own ankles as the tracker and
// its own skeleton as the avatar.
struct WipTrialEval {
  std::string name;
  double duration = 0, leg_length = 0;
  std::vector<SwingEvent> truth, detected, detected_noisy;
  StepScore steps, steps_noisy;  // lenient: overlapping swings (secondary)
  StrictScore strict, strict_100, strict_noisy;  // +-200 ms, +-100 ms, +-200 ms noisy
  std::vector<StillSegment> still;
  Agreement depth, baseline_depth;
  std::vector<wip::Info> frames;       // clean run
  DepthTrack true_depth;               // at the tracker rate
  std::vector<double> baseline_z[2];   // baseline ankle depths per frame
  std::string subject;                 // CMU subject (the name before '_'): the cross-validation fold
  bool turning = false;                // true_depth.heading_range_deg > kTurningDegrees
  std::vector<wip::LearnSample> learn; // training samples of the clean run (learned mapping)
  Agreement depth_segment[kDepthSegments];    // the document's mapping by DepthSegment
  Agreement depth_learned;             // learned mapping, table built without this subject (samples 0 = n/a)
  Agreement learned_segment[kDepthSegments];  // the same by DepthSegment
  std::vector<double> learned_z[2];    // its IK-target depths per frame
  SpeedTrial speed;                    // the avatar's travel against the pelvis's (clean run)
};
// The CMU subject of a trial name ("105_02" -> "105").
std::string subject_of(const std::string& trial);
// The learned mapping's training samples of one trial: its own ankles through
// the method (the document's mapping, opt's settings and rate) paired with
// its real foot depths after opt.settle, as `wip eval` collects them.
std::vector<wip::LearnSample> trial_learning_samples(const Motion& trial, const WipEvalOptions& opt);
// One learned table per held-out subject, each built only from the samples of
// the other subjects (nullopt, logged, when they are too few): the tables the
// learned mapping is scored with, in `wip eval` and `eval combined`.
std::map<std::string, std::optional<wip::LearnedMapping>> learned_tables_by_subject(
    const std::map<std::string, std::vector<wip::LearnSample>>& samples_by_subject,
    const std::function<void(const std::string&)>& log = {});
// Runs the trial again with the learned mapping `table` and scores its depths
// against e.true_depth (fills e.depth_learned, e.learned_z).
void evaluate_learned_depth(const Motion& trial, const wip::LearnedMapping& table, const WipEvalOptions& opt,
                            WipTrialEval& e);
// `cycle`: the baseline's in-place walk cycle (wip::extract_walk_cycle).
WipTrialEval evaluate_wip_trial(const Motion& trial, const std::string& name, const Motion& cycle,
                                const WipEvalOptions& opt, int trial_index = 0);

// The whole evaluation over a folder's trials.
struct WipEvalRun {
  std::vector<std::string> files;  // BVH trials (T-pose frame 0 dropped)
  std::string data;                // the folder, as reported
  std::string note;                // e.g. why a fallback folder was used ("" = none)
  std::string clip;                // the baseline's walking clip (a BVH path)
  std::string out;                 // output folder (created)
  WipEvalOptions options;
  std::function<void(const std::string&)> log;  // progress and skipped trials (may be empty)
  bool cross_validate_detector = false;  // also choose the adaptive detector's parameters by subject (wip_tune.hpp)
};
// Step detection of one detector over all trials (strict scores, false steps).
struct DetectorSummary {
  std::string name;  // "document" or "adaptive"
  StrictScore strict, strict_100, strict_noisy;
  int false_steps = 0, false_steps_noisy = 0;
  double false_steps_per_minute = NAN, false_steps_per_minute_noisy = NAN;
};
struct WipEvalSummary {
  int trials = 0, skipped = 0;
  StepScore steps, steps_noisy, steps_fixed;  // lenient overlap scores (secondary)
  StrictScore strict, strict_100, strict_noisy, strict_fixed;
  std::vector<StillSegment> still;
  double still_minutes = 0, false_steps_per_minute = NAN, false_steps_per_minute_noisy = NAN;
  Agreement depth, baseline_depth;
  // Depth agreement by trial class (normal / turning walks), the document's
  // mapping and the learned one cross-validated by subject.
  Agreement depth_normal, depth_turning, learned, learned_normal, learned_turning;
  int learned_trials = 0;
  // Both mappings by DepthSegment (where the depth error comes from).
  Agreement depth_segment[kDepthSegments], learned_segment[kDepthSegments];
  DetectorSummary detectors[2];      // [0] the document's detector (before), [1] the adaptive one (after)
  bool cross_validated = false;      // the adaptive detector's parameters were also chosen by subject (below)
  StrictScore cv_strict, cv_noisy;   // held-out subjects pooled
  double cv_false_per_minute = NAN, cv_false_per_minute_noisy = NAN;
  std::string tuning_markdown, tuning_json;  // the cross-validation's report section and JSON
  SpeedSummary speed;                // walking speed against the capture's (wip_speed.hpp)
  std::vector<std::string> written;  // report.md, report.json
};
// Evaluates every trial (with the adaptive and the document's fixed
// thresholds), writes report.json, report.md, summary.png and <trial>.png
// into `out`. Throws if no trial could be evaluated.
WipEvalSummary run_wip_evaluation(const WipEvalRun& run);

// What a run of `legwork wip` did, as printed lines: frames, steps, distance,
// mean speed; with `truth` (true swings of the input) the step scores.
std::string describe_wip_run(std::span<const wip::Info> frames, double rate, std::span<const SwingEvent> truth);

// Plots of one run of `legwork wip`: the document's Figure 2-like curves
// (heights, velocities, phases, depths, speed) and, when `strip` lists
// frames of `avatar`, a side-view strip of the avatar under them.
void plot_wip_phases(const std::string& path, const std::string& title, std::span<const wip::Info> frames,
                     const Motion& avatar, const std::vector<int>& strip, const std::vector<double>* baseline_z,
                     const wip::GaitSettings& gait);
// Frames for the side strip: "a,b,c" (checked against the frame count) or
// six spread over the first well-established steps.
std::vector<int> strip_frames(const std::string& spec, std::span<const wip::Info> frames);

}  // namespace legwork::eval
