#pragma once
// Forward-speed estimators for walking in place, updated at gait transitions
// (the document adapts the speed at mid-swing and terminal swing). Pluggable:
// derive from SpeedEstimator and hand it to the WipWorkspace. Runtime: no
// allocation. Speeds in m/s.
#include <legwork/wip/gait.hpp>

namespace legwork::wip {

// What an estimator sees each update.
struct SpeedInput {
  double time = 0, dt = 0;
  int foot = 0;                 // the foot whose event this is (per-foot calls)
  unsigned events = 0;          // GaitEvent bits of this foot on this update
  double v = 0;                 // vertical velocity of this foot, m/s
  bool walking = true;          // false once the stop rule fired
};

class SpeedEstimator {
 public:
  virtual ~SpeedEstimator() = default;
  virtual void reset() = 0;
  // Called once per foot per update.
  virtual void observe(const SpeedInput& in) = 0;
  // Target forward speed after this update (before the cap and smoothing).
  virtual double target_speed(double time) const = 0;
};

// Bruno et al.'s step-speed model: speed = gain * the mean vertical foot speed
// since the foot's previous gait transition, updated at mid-swing and terminal
// swing. The speed drops to zero when no foot has been in swing for
// `idle_stop` seconds.
class StepSpeedEstimator final : public SpeedEstimator {
 public:
  double gain = 2.15;     // m/s of forward speed per m/s of mean vertical foot speed
  double idle_stop = 0.8; // s without swing -> 0
  void reset() override;
  void observe(const SpeedInput& in) override;
  double target_speed(double time) const override;

 private:
  double integral_[2] = {0, 0}, elapsed_[2] = {0, 0};
  double speed_ = 0, last_swing_time_ = -1e9;
};

// GUD-WIP-style step-frequency model: speed = stride_per_step * step
// frequency, the frequency from the interval between successive foot-offs.
class StepFrequencyEstimator final : public SpeedEstimator {
 public:
  double stride_per_step = 0.65;  // m per step (2 steps/s -> 1.3 m/s)
  double max_interval = 1.5;      // s: longer gaps do not count as a cadence
  double idle_stop = 0.8;
  void reset() override;
  void observe(const SpeedInput& in) override;
  double target_speed(double time) const override;

 private:
  double last_off_ = -1e9, speed_ = 0, last_swing_time_ = -1e9;
};

// Gain of the step-speed model that maps a recorded stepping (mean vertical
// foot speed over swings) to `target` m/s (the document: ~1.3 m/s for
// comfortable in-place stepping).
double calibrate_step_speed_gain(double mean_vertical_swing_speed, double target = 1.3);

}  // namespace legwork::wip
