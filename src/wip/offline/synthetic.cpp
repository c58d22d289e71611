#include <legwork/wip/offline/synthetic.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

namespace legwork::wip {

namespace {

// Swings alternate left, right, ...; a swing overlapping a pause is skipped.
std::vector<SwingEvent> synthetic_swings(const SyntheticOptions& o) {
  std::vector<SwingEvent> swings;
  const double step_period = 1.0 / o.cadence;
  const double swing = std::clamp(o.swing_fraction, 0.1, 1.6) * step_period;
  const double lift[2] = {o.step_height, o.step_height * (1.0 - o.asymmetry)};
  auto paused = [&](double t0, double t1) {
    return o.pause_length > 0 && t1 > o.pause_start && t0 < o.pause_start + o.pause_length;
  };
  int foot = kLeft;
  for (double t0 = o.stand_time; t0 + swing < o.duration; t0 += step_period) {
    if (paused(t0, t0 + swing)) {
      foot = kLeft;  // resume with the left foot, like a fresh start
      continue;
    }
    swings.push_back({foot, t0, t0 + swing, lift[foot]});
    foot = 1 - foot;
  }
  return swings;
}

// Height of foot f's ankle above standing at time t; next[f] skips finished swings.
double lift_at(const std::vector<SwingEvent>& swings, int f, double t, std::size_t& next) {
  for (std::size_t k = next; k < swings.size(); ++k) {
    const auto& sw = swings[k];
    if (sw.foot != f) continue;
    if (sw.off > t) break;
    if (t <= sw.strike) {
      // Quick lift, slower lowering: the phase is skewed toward early swing.
      const double u = (t - sw.off) / (sw.strike - sw.off);
      const double w = std::pow(u, 0.8);
      return sw.apex * std::pow(std::sin(kPi * w), 2);
    }
    next = k + 1;
  }
  return 0;
}

}  // namespace

SyntheticTrack synthetic_stepping(const SyntheticOptions& o) {
  if (!(o.rate > 0) || !(o.duration > 0) || !(o.cadence > 0))
    throw Error("synthetic stepping: rate, duration and cadence must be positive");
  const double n_real = std::floor(o.duration * o.rate) + 1;
  if (!(n_real <= static_cast<double>(o.max_frames)))
  {
    char buf[200];
    std::snprintf(buf, sizeof buf, "synthetic stepping: %g s at %g Hz is more than the limit of %zu frames", o.duration,
                  o.rate, o.max_frames);
    throw Error(buf);
  }
  SyntheticTrack tr;
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> jitter(0.0, 1.0);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  tr.swings = synthetic_swings(o);
  const int n = static_cast<int>(n_real);
  tr.frames.resize(static_cast<std::size_t>(n));
  std::size_t next[2] = {0, 0};
  for (int i = 0; i < n; ++i) {
    const double t = i / o.rate;
    TrackerFrame& s = tr.frames[static_cast<std::size_t>(i)];
    s.time = t;
    for (int f = 0; f < 2; ++f) {
      const double h = lift_at(tr.swings, f, t, next[f]);
      const double side = f == kLeft ? 0.5 : -0.5;
      DevicePose& d = s.foot(f);
      d.position = Vec3(side * o.stance_width + o.noise * jitter(rng), o.floor_y + o.ankle_height + h + o.noise * jitter(rng),
                        0.02 * h + o.noise * jitter(rng));
      d.valid = true;
      if (uni(rng) < o.drop_rate) d.valid = false;
      if (uni(rng) < o.nan_rate) {
        d.valid = false;
        d.position = Vec3::Constant(std::nan(""));
      }
    }
  }
  return tr;
}

void add_tracker_noise(std::vector<TrackerFrame>& frames, double noise, double drop_rate, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> jitter(0.0, 1.0);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  for (auto& s : frames)
    for (int f = 0; f < 2; ++f) {
      DevicePose& d = s.foot(f);
      d.position += noise * Vec3(jitter(rng), jitter(rng), jitter(rng));
      if (uni(rng) < drop_rate) d.valid = false;
    }
}

}  // namespace legwork::wip
