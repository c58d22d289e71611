#include <legwork/wip/learned.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::wip {

namespace {
// Node index and fraction of a coordinate in [0, 2].
void locate(double c, int& i, double& t) {
  constexpr int n = LearnedMapping::kNodes;
  const double x = std::clamp(std::isfinite(c) ? c : 0.0, 0.0, 2.0) * (n - 1) / 2.0;
  i = std::min(static_cast<int>(x), n - 2);
  t = x - i;
}
}  // namespace

double LearnedMapping::lookup(double own, double other, int lead) const {
  if (lead < 0) return 0.5 * (lookup(own, other, 0) + lookup(own, other, 1));
  int i, j;
  double s, t;
  locate(own, i, s);
  locate(other, j, t);
  const int l = lead > 0 ? 1 : 0;
  return (1 - s) * ((1 - t) * at(l, i, j) + t * at(l, i, j + 1)) + s * ((1 - t) * at(l, i + 1, j) + t * at(l, i + 1, j + 1));
}

double LearnedMapping::gain(double apex) const {
  if (!std::isfinite(apex)) return 1;
  return std::clamp(1 + gain_slope * (apex - apex_mean), gain_min, gain_max);
}

double cycle_coordinate(const GaitMachine& g, const GaitSettings& p, double h) {
  const double hh = std::max(std::isfinite(h) ? h : 0.0, 0.0);
  const bool rising = g.phase == GaitPhase::DoubleSupport || g.phase == GaitPhase::InitialSwing;
  if (rising) return std::min(hh / std::max(g.apex_estimate, p.min_h1), 1.0);
  return 2 - std::min(hh / std::max(g.apex, p.min_h1), 1.0);
}

}  // namespace legwork::wip
