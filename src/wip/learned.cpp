#include <legwork/wip/learned.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::wip {

void locate_cycle(double c, int& i, double& t) {
  constexpr int n = LearnedMapping::kNodes;
  const double x = std::clamp(std::isfinite(c) ? c : 0.0, 0.0, 2.0) * (n - 1) / 2.0;
  i = std::min(static_cast<int>(x), n - 2);
  t = x - i;
}

void locate_since(double since, int& k, double& t) {
  const auto& s = LearnedMapping::kSince;
  const double x = std::clamp(std::isfinite(since) ? since : s.back(), s.front(), s.back());
  k = 0;
  while (k < LearnedMapping::kSinceNodes - 2 && x > s[static_cast<std::size_t>(k + 1)]) ++k;
  t = (x - s[static_cast<std::size_t>(k)]) / (s[static_cast<std::size_t>(k + 1)] - s[static_cast<std::size_t>(k)]);
}

double LearnedMapping::lookup(double own, double other, int lead, double since) const {
  if (lead < 0) return 0.5 * (lookup(own, other, 0, since) + lookup(own, other, 1, since));
  int i, j, k;
  double s, t, u;
  locate_cycle(own, i, s);
  locate_cycle(other, j, t);
  locate_since(since, k, u);
  const int l = lead > 0 ? 1 : 0;
  double v = 0;
  for (int dk = 0; dk < 2; ++dk) {
    const double wk = dk ? u : 1 - u;
    v += wk * ((1 - s) * ((1 - t) * at(l, k + dk, i, j) + t * at(l, k + dk, i, j + 1)) +
               s * ((1 - t) * at(l, k + dk, i + 1, j) + t * at(l, k + dk, i + 1, j + 1)));
  }
  return v;
}

double LearnedMapping::amplitude(double apex, double cadence) const {
  const double a = amplitude_intercept + amplitude_slope * (std::isfinite(apex) ? apex : apex_mean) +
                   cadence_slope * (std::isfinite(cadence) ? cadence : cadence_mean);
  return std::clamp(a, amplitude_min, amplitude_max);
}

double LearnedMapping::turn_gain(double turn_rate) const {
  const double r = std::clamp(std::isfinite(turn_rate) ? std::abs(turn_rate) : 0.0, 0.0, kMaxTurnRate);
  return std::clamp(turn_intercept + turn_slope * r, 0.0, kMaxTurnGain);
}

double cycle_coordinate(const GaitMachine& g, const GaitSettings& p, double h) {
  const double hh = std::max(std::isfinite(h) ? h : 0.0, 0.0);
  const bool rising = g.phase == GaitPhase::DoubleSupport || g.phase == GaitPhase::InitialSwing;
  if (rising) return std::min(hh / std::max(g.apex_estimate, p.min_h1), 1.0);
  return 2 - std::min(hh / std::max(g.apex, p.min_h1), 1.0);
}

}  // namespace legwork::wip
