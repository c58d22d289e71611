// Walking speed of walking in place against the capture's real speed.
#include <legwork/eval/wip_speed.hpp>

#include <algorithm>
#include <cmath>
#include <map>

namespace legwork::eval {

double travelled_distance(std::span<const Vec3> positions, double rate, double t0, double t1, double window) {
  const int n = static_cast<int>(positions.size());
  if (n < 2 || !(rate > 0)) return 0;
  const int w = std::max(0, static_cast<int>(std::lround(window * rate)));
  auto smoothed = [&](int i) {
    Vec3 s = Vec3::Zero();
    const int a = std::max(0, i - w), b = std::min(n - 1, i + w);
    for (int k = a; k <= b; ++k) s += positions[static_cast<std::size_t>(k)];
    s /= (b - a + 1);
    s.y() = 0;
    return s;
  };
  const int first = std::clamp(static_cast<int>(std::ceil(t0 * rate - 1e-9)), 0, n - 1);
  const int last = std::clamp(static_cast<int>(std::floor(t1 * rate + 1e-9)), 0, n - 1);
  double d = 0;
  Vec3 prev = smoothed(first);
  for (int i = first + 1; i <= last; ++i) {
    const Vec3 p = smoothed(i);
    d += (p - prev).norm();
    prev = p;
  }
  return d;
}

double wip_travelled(std::span<const wip::Info> frames, double t0, double t1) {
  double a = NAN, b = NAN;
  for (const auto& f : frames) {
    if (f.time < t0 || f.time > t1) continue;
    if (!std::isfinite(a)) a = f.distance;
    b = f.distance;
  }
  return std::isfinite(a) ? b - a : 0;
}

namespace {

// Pooled speeds and the RMS of per-trial mean speed errors, generated
// distances scaled by `scale` (a gain change).
struct Pooled {
  double real = 0, wip = 0, seconds = 0, se2 = 0;
  int n = 0;
  void add(const SpeedTrial& t, double scale) {
    real += t.real_distance;
    wip += scale * t.wip_distance;
    seconds += t.seconds;
    const double e = scale * t.wip_speed() - t.real_speed();
    se2 += e * e;
    ++n;
  }
  double real_speed() const { return seconds > 0 ? real / seconds : 0; }
  double wip_speed() const { return seconds > 0 ? wip / seconds : 0; }
  double rms() const { return n > 0 ? std::sqrt(se2 / n) : 0; }
};

}  // namespace

SpeedSummary summarize_speed(std::span<const SpeedTrial> trials, double gain) {
  SpeedSummary s;
  s.gain = gain;
  Pooled all;
  std::map<std::string, Pooled> by_subject;
  for (const auto& t : trials) {
    all.add(t, 1.0);
    by_subject[t.subject].add(t, 1.0);
  }
  if (!(all.wip > 0)) throw Error("walking speed: the method travelled no distance on any trial (no steps detected?)");
  s.trials = all.n;
  s.real_speed = all.real_speed();
  s.wip_speed = all.wip_speed();
  s.rms_error = all.rms();
  s.calibrated_gain = gain * all.real / all.wip;
  // Cross-validated by subject: each subject's gain from the other subjects' walks.
  Pooled cv;
  for (const auto& [subject, own] : by_subject) {
    const double real = all.real - own.real, wip = all.wip - own.wip;
    const double scale = wip > 0 ? real / wip : 1.0;
    Pooled held;
    for (const auto& t : trials)
      if (t.subject == subject) held.add(t, scale), cv.add(t, scale);
    s.folds.push_back({subject, gain * scale, held.real_speed(), held.wip_speed()});
  }
  s.cv_wip_speed = cv.wip_speed();
  s.cv_rms_error = cv.rms();
  return s;
}

}  // namespace legwork::eval
