#pragma once
// Low-pass Butterworth filter designed at run time from cutoff and sample
// rate (bilinear transform with pre-warping, so the response is exactly -3 dB
// at the cutoff for any rate). Cascaded biquads (+ one first-order section for
// odd orders). Runtime: fixed-size state, no allocation; not thread-safe per
// instance.
#include <array>

namespace legwork::wip {

class Butterworth {
 public:
  static constexpr int kMaxOrder = 8;

  Butterworth() = default;
  // order 1..8; cutoff in Hz, 0 < cutoff < rate/2 (clamped just below Nyquist).
  Butterworth(int order, double cutoff_hz, double rate_hz);

  // Filters one sample. A non-finite input repeats the previous input (the
  // output never becomes NaN). The first sample primes the state to steady
  // state at that value, so the output starts without a transient.
  double step(double x);
  // Sets the state to steady state at value x.
  void reset(double x);
  bool primed() const { return primed_; }

  // |H(f)| of the designed filter at frequency f (Hz); for tests and docs.
  double magnitude(double f_hz) const;
  int order() const { return order_; }
  double cutoff() const { return cutoff_; }
  double rate() const { return rate_; }

 private:
  struct Section {
    double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;  // a0 = 1
    double z1 = 0, z2 = 0;                            // direct form II transposed
  };
  std::array<Section, (kMaxOrder + 1) / 2> sections_{};
  int count_ = 0, order_ = 0;
  double cutoff_ = 0, rate_ = 0, last_input_ = 0;
  bool primed_ = false;
};

}  // namespace legwork::wip
