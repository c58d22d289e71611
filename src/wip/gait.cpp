#include <legwork/wip/gait.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::wip {

void FootSignal::init(const SignalSettings& p) {
  filter = Butterworth(p.order, p.cutoff, p.rate);
  detect_filter = Butterworth(p.order, p.detect_cutoff, p.rate);
  hd = vd = baseline = noise = 0;
  capacity = std::clamp(static_cast<int>(std::lround(p.buffer_seconds * p.rate)), 2, kCapacity);
  head = -1;
  size = 0;
  h = v = 0;
  confidence = 0;
  held_time = 0;
}

void FootSignal::push(const SignalSettings& p, double y, bool valid, double dt, bool in_support) {
  valid = valid && std::isfinite(y);
  if (valid) {
    raw = y;
    held_time = 0;
    // Confidence recovers over the same time constant it decays with.
    confidence = std::min(1.0, confidence + dt / std::max(p.confidence_tau, 1e-6));
    if (!has_floor) {
      floor = y;
      has_floor = true;
    }
  } else {
    held_time += dt;
    confidence *= std::exp(-dt / std::max(p.confidence_tau, 1e-6));
    if (!has_floor) return;  // nothing seen yet
  }
  const double yf = filter.step(raw);  // holds the last value over dropouts
  const double yd = detect_filter.step(raw);
  if (p.floor_tau > 0) {
    if (yf < floor) floor = yf;
    else if (in_support && valid) floor += (yf - floor) * (1 - std::exp(-dt / p.floor_tau));
  }
  const double prev = size > 0 ? ring[static_cast<std::size_t>(head)] : yf - floor;
  head = (head + 1) % capacity;
  ring[static_cast<std::size_t>(head)] = yf - floor;
  size = std::min(size + 1, capacity);
  h = yf - floor;
  // Velocity of the filtered height: the raw one is too noisy at 30 Hz and has
  // often fallen below V1 by the time the (delayed) filtered height crosses H1.
  v = dt > 0 ? (h - prev) / dt : 0;
  update_detection(p, yd - floor, raw - yf, valid, dt, in_support);
}

void FootSignal::update_detection(const SignalSettings& p, double height, double jitter, bool valid, double dt,
                                  bool in_support) {
  const bool first = size <= 1;
  const double d = height - baseline;
  vd = first || !(dt > 0) ? 0 : (d - hd) / dt;
  if (in_support && valid) {
    // The baseline is the running mean of the stance height (not its minimum:
    // jitter would pull a minimum down and fake a lift); the noise is the running RMS of the raw height's jitter about the 4 Hz
    // signal (tracker noise, not the slow heel rise of real stance).
    const double a = 1 - std::exp(-dt / std::max(p.baseline_tau, 1e-6));
    const double b = 1 - std::exp(-dt / std::max(p.noise_tau, 1e-6));
    if (first) baseline = height;
    baseline += a * (height - baseline);
    noise = std::sqrt(noise * noise + b * (jitter * jitter - noise * noise));
  }
  hd = height - baseline;
}

double FootSignal::recent(int back) const {
  if (size == 0) return 0;
  back = std::clamp(back, 0, size - 1);
  return ring[static_cast<std::size_t>((head - back + capacity) % capacity)];
}

double FootSignal::recent_max() const {
  double m = size > 0 ? recent(0) : 0;
  for (int i = 1; i < size; ++i) m = std::max(m, recent(i));
  return m;
}

std::string_view phase_name(GaitPhase p) {
  switch (p) {
    case GaitPhase::DoubleSupport: return "double_support";
    case GaitPhase::InitialSwing: return "initial_swing";
    case GaitPhase::MidSwing: return "mid_swing";
    case GaitPhase::TerminalSwing: return "terminal_swing";
  }
  return "?";
}

void GaitMachine::init(const GaitSettings& p) {
  *this = GaitMachine{};
  apex_estimate = p.h1 / std::max(p.height_fraction, 1e-6);
  up_estimate = p.v1 / std::max(p.velocity_fraction, 1e-6);
  down_estimate = p.v2 / std::max(p.velocity_fraction, 1e-6);
}

bool GaitMachine::at_rest(const GaitSettings& p) const {
  return p.rest_time > 0 && phase == GaitPhase::DoubleSupport && rest >= p.rest_time;
}

double GaitMachine::h1(const GaitSettings& p) const {
  if (p.detector == StepDetector::Adaptive) {
    double lift = std::max({p.lift_fraction * apex_estimate, p.noise_factor * noise, p.min_lift});
    if (at_rest(p)) lift = std::min(lift, std::max({p.rest_lift, p.rest_noise_factor * noise, p.min_lift}));
    return std::min(lift, p.h1);
  }
  return p.adaptive ? std::clamp(p.height_fraction * apex_estimate, p.min_h1, p.h1) : p.h1;
}
double GaitMachine::v1(const GaitSettings& p) const {
  if (p.detector == StepDetector::Adaptive) {
    double rise = std::max({p.rise_fraction * up_estimate, p.rise_noise_factor * noise, p.min_rise});
    if (at_rest(p)) rise = std::min(rise, std::max({p.rest_rise, p.rise_noise_factor * noise, p.min_rise}));
    return std::min(rise, p.v1);
  }
  return p.adaptive ? std::clamp(p.velocity_fraction * up_estimate, p.min_v1, p.v1) : p.v1;
}
double GaitMachine::v2(const GaitSettings& p) const {
  if (p.detector == StepDetector::Adaptive)
    return std::min(std::max({p.velocity_fraction * down_estimate, p.rise_noise_factor * noise, p.min_rise}), p.v2);
  return p.adaptive ? std::clamp(p.velocity_fraction * down_estimate, p.min_v1, p.v2) : p.v2;
}

unsigned GaitMachine::update(const GaitSettings& p, double h, double v, double confidence, double dt) {
  time_in_phase += dt;
  const double H1 = h1(p), V1 = v1(p), V2 = v2(p);
  const double land = p.land_fraction * H1;
  unsigned ev = kEventNone;
  auto go = [&](GaitPhase next, unsigned e) {
    phase = next;
    steady = 0;
    time_in_phase = 0;
    ev |= e;
  };
  auto finish_swing = [&](unsigned e) {
    // Learn the user's step from complete swings that cleared the noise floor.
    if (apex > p.min_h1) {
      const double w = p.estimate_rate;
      apex_estimate += w * (apex - apex_estimate);
      up_estimate += w * (peak_up - up_estimate);
      if (peak_down > 0) down_estimate += w * (peak_down - down_estimate);
      ++swings;
    }
    go(GaitPhase::DoubleSupport, e);
  };
  if (in_swing(phase)) swing_time += dt;
  // The adaptive detector's minimum swing (min_swing_time): no landing before it.
  const bool can_land = p.detector != StepDetector::Adaptive || !(p.min_swing_time > 0) || swing_time >= p.min_swing_time;
  if (in_swing(phase)) {
    apex = std::max(apex, h);
    peak_up = std::max(peak_up, v);
    peak_down = std::max(peak_down, -v);
    if (confidence < p.lost_confidence) {
      go(GaitPhase::DoubleSupport, kEventLost | kEventFootStrike);
      return ev;
    }
  }
  switch (phase) {
    case GaitPhase::DoubleSupport:
      if (time_in_phase >= p.min_stance_time && h > H1 && v > V1 && confidence >= p.lost_confidence) {
        apex = h;
        peak_up = v;
        peak_down = 0;
        swing_time = 0;
        go(GaitPhase::InitialSwing, kEventFootOff);
      }
      break;
    case GaitPhase::InitialSwing:
      if (can_land && h < land)
        finish_swing(kEventFootStrike);
      else if (v < V1 || time_in_phase > p.max_ascent_time)
        go(GaitPhase::MidSwing, kEventMidSwing);
      break;
    case GaitPhase::MidSwing:
      if (can_land && h < land)
        finish_swing(kEventFootStrike);
      else if (v < -V2 || h < H1)
        go(GaitPhase::TerminalSwing, kEventTerminal);
      break;
    case GaitPhase::TerminalSwing:
      steady = std::abs(v) < V1 ? steady + dt : 0.0;
      if (can_land && (h < land || (h < H1 && v > -V1 && time_in_phase > dt * 1.5) || (p.settle_time > 0 && steady >= p.settle_time)))
        finish_swing(kEventFootStrike);
      break;
  }
  return ev;
}

}  // namespace legwork::wip
