#include <legwork/wip/mapping.hpp>

#include <legwork/core/types.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::wip {

namespace {
double c_of(const StepShape& k, double h) { return std::cos(2 * kPi * std::clamp(h, 0.0, k.H) / k.lambda()); }
}  // namespace

double first_step_swing(const StepShape& k, double h, bool up) {
  const double c = c_of(k, h);
  return up ? -0.25 * k.S * c + 0.25 * k.S : 0.25 * k.S * c + 0.25 * k.S;
}
double first_step_support(const StepShape& k, double h, bool up) {
  const double c = c_of(k, h);
  return up ? 0.25 * k.S * c - 0.25 * k.S : -0.25 * k.S * c - 0.25 * k.S;
}
double next_step_swing(const StepShape& k, double h, bool up) {
  const double c = c_of(k, h);
  const double hc = std::clamp(h, 0.0, k.H);
  return up ? -0.5 * k.S * c : 0.5 * k.S * c + 0.25 * k.S * std::sin(4 * kPi * hc / k.lambda());
}
double next_step_support(const StepShape& k, double h, bool up) {
  const double c = c_of(k, h);
  return up ? 0.5 * k.S * c : -0.5 * k.S * c;
}
double body_drop(double L, double z_trail) {
  const double z = std::min(std::abs(z_trail), L);
  return L - std::sqrt(L * L - z * z);
}

}  // namespace legwork::wip
