#include <legwork/wip/filter.hpp>

#include <legwork/core/types.hpp>

#include <algorithm>
#include <cmath>
#include <complex>

namespace legwork::wip {

Butterworth::Butterworth(int order, double cutoff_hz, double rate_hz)
    : order_(std::clamp(order, 1, kMaxOrder)), cutoff_(cutoff_hz), rate_(rate_hz) {
  const double fc = std::clamp(cutoff_hz, 1e-6 * rate_hz, 0.499 * rate_hz);
  cutoff_ = fc;
  // Pre-warped analogue cutoff: the digital response is -3 dB exactly at fc.
  const double k = std::tan(kPi * fc / rate_hz);
  const double k2 = k * k;
  count_ = 0;
  // Pole pairs of the analogue prototype: Q_i = 1 / (2 sin((2i+1) pi / (2N))).
  for (int i = 0; i < order_ / 2; ++i) {
    const double q = 1.0 / (2.0 * std::sin((2 * i + 1) * kPi / (2.0 * order_)));
    const double norm = 1.0 / (1.0 + k / q + k2);
    Section& s = sections_[static_cast<std::size_t>(count_++)];
    s.b0 = k2 * norm;
    s.b1 = 2 * s.b0;
    s.b2 = s.b0;
    s.a1 = 2 * (k2 - 1) * norm;
    s.a2 = (1 - k / q + k2) * norm;
  }
  if (order_ % 2 == 1) {  // the real pole of odd orders
    Section& s = sections_[static_cast<std::size_t>(count_++)];
    s.b0 = k / (1 + k);
    s.b1 = s.b0;
    s.b2 = 0;
    s.a1 = (k - 1) / (k + 1);
    s.a2 = 0;
  }
}

void Butterworth::reset(double x) {
  for (int i = 0; i < count_; ++i) {
    Section& s = sections_[static_cast<std::size_t>(i)];
    // Unity DC gain: every section's output equals x in steady state.
    s.z2 = s.b2 * x - s.a2 * x;
    s.z1 = s.b1 * x - s.a1 * x + s.z2;
  }
  last_input_ = x;
  primed_ = true;
}

double Butterworth::step(double x) {
  if (!std::isfinite(x)) x = last_input_;
  if (!primed_) reset(x);
  last_input_ = x;
  double y = x;
  for (int i = 0; i < count_; ++i) {
    Section& s = sections_[static_cast<std::size_t>(i)];
    const double in = y;
    y = s.b0 * in + s.z1;
    s.z1 = s.b1 * in - s.a1 * y + s.z2;
    s.z2 = s.b2 * in - s.a2 * y;
  }
  return y;
}

double Butterworth::magnitude(double f_hz) const {
  const std::complex<double> z1 = std::polar(1.0, -2 * kPi * f_hz / rate_);  // z^-1
  std::complex<double> h = 1.0;
  for (int i = 0; i < count_; ++i) {
    const Section& s = sections_[static_cast<std::size_t>(i)];
    h *= (s.b0 + s.b1 * z1 + s.b2 * z1 * z1) / (1.0 + s.a1 * z1 + s.a2 * z1 * z1);
  }
  return std::abs(h);
}

}  // namespace legwork::wip
