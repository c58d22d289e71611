#pragma once
// Evaluation of walking-in-place on real walking (offline): true gait events
// from mocap, step detection scores, true foot-forward offsets and curve
// agreement. May allocate and throw legwork::Error.
#include <legwork/wip/baseline.hpp>
#include <legwork/wip/tracker.hpp>
#include <legwork/wip/wip.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace legwork::wip {

// Ground-truth contact: a foot is down when its ankle (heel) or toe is within
// `height_tol` of its local floor (rolling minimum over +-floor_window) and
// moving slower than `speed_tol`. Foot-off = the toe leaves, foot-strike =
// the first contact again.
struct TruthParams {
  double height_tol = 0.03;   // m
  double speed_tol = 0.5;     // m/s
  double floor_window = 1.0;  // s each side
  double min_swing = 0.15;    // s: shorter lifts are not steps
  double min_stance = 0.05;   // s: shorter touch-downs do not split a swing
};
std::vector<SwingEvent> true_swings(const Motion& m, const TruthParams& p = {});

// Swings seen by the gait machines (foot-off to foot-strike events).
std::vector<SwingEvent> detected_swings(std::span<const WipFrame> frames);

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

// True forward offset of each ankle from the pelvis along the walking heading
// (from the hip line, smoothed over +-0.5 s), at `rate` Hz from t = 0.
struct DepthTrack {
  std::vector<double> time;
  std::vector<double> z[2];
};
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

struct EvalOptions {
  WipParams params;            // the method's parameters (rate = tracker rate)
  TruthParams truth;
  double noise = 0.015;        // Kinect-like jitter for the noisy run, m
  double drop_rate = 0.02;     // dropped samples in the noisy run
  std::uint64_t seed = 1;      // noise seed (mixed with the trial index)
  double settle = 0.5;         // s at the start ignored (filter and floor settle)
};

// One trial driven through the method with its own ankles as the tracker and
// its own skeleton as the avatar.
struct TrialEval {
  std::string name;
  double duration = 0, leg_length = 0;
  std::vector<SwingEvent> truth, detected, detected_noisy;
  StepScore steps, steps_noisy;
  Agreement depth, baseline_depth;
  std::vector<WipFrame> frames;        // clean run
  DepthTrack true_depth;               // at the tracker rate
  std::vector<double> baseline_z[2];   // baseline ankle depths per frame
};
// `cycle`: the baseline's in-place walk cycle (extract_walk_cycle).
TrialEval evaluate_trial(const Motion& trial, const std::string& name, const Motion& cycle, const EvalOptions& opt,
                         int trial_index = 0);

}  // namespace legwork::wip
