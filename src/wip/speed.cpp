#include <legwork/wip/speed.hpp>

#include <cmath>

namespace legwork::wip {

void StepSpeedEstimator::reset() {
  integral_[0] = integral_[1] = elapsed_[0] = elapsed_[1] = 0;
  speed_ = 0;
  last_swing_time_ = -1e9;
}

void StepSpeedEstimator::observe(const SpeedInput& in) {
  const int f = in.foot & 1;
  integral_[f] += std::abs(in.v) * in.dt;
  elapsed_[f] += in.dt;
  if (in.events & (kEventMidSwing | kEventTerminal)) {
    if (elapsed_[f] > 0) speed_ = gain * integral_[f] / elapsed_[f];
    last_swing_time_ = in.time;
  }
  if (in.events & kEventFootOff) last_swing_time_ = in.time;
  if (in.events) integral_[f] = elapsed_[f] = 0;  // averages run between transitions
  if (!in.walking) speed_ = 0;
}

double StepSpeedEstimator::target_speed(double time) const {
  return time - last_swing_time_ > idle_stop ? 0.0 : speed_;
}

void StepFrequencyEstimator::reset() {
  last_off_ = -1e9;
  speed_ = 0;
  last_swing_time_ = -1e9;
}

void StepFrequencyEstimator::observe(const SpeedInput& in) {
  if (in.events & kEventFootOff) {
    const double gap = in.time - last_off_;
    if (gap > 1e-3 && gap < max_interval) speed_ = stride_per_step / gap;
    last_off_ = in.time;
  }
  if (in.events & (kEventFootOff | kEventMidSwing | kEventTerminal)) last_swing_time_ = in.time;
  if (!in.walking) speed_ = 0;
}

double StepFrequencyEstimator::target_speed(double time) const {
  return time - last_swing_time_ > idle_stop ? 0.0 : speed_;
}

double calibrate_step_speed_gain(double mean_vertical_swing_speed, double target) {
  return mean_vertical_swing_speed > 1e-6 ? target / mean_vertical_swing_speed : 0.0;
}

}  // namespace legwork::wip
