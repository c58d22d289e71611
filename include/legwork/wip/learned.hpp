#pragma once
// A walking-in-place depth mapping learned from real walking (issue 13, item
// 3), beside the document's equations 1-4. Each foot's gait state is reduced
// to a cycle coordinate c in [0, 2] (0 at rest, h / apex while rising, 2 - h /
// apex while descending); a table over (own c, other foot's c, which foot
// landed last) gives the foot's fore-aft offset from the pelvis divided by the
// leg length, averaged over real CMU walks run through the same filters and
// gait machines (so their lag is learned too), divided by each walk's depth
// amplitude; the amplitude is learned as a linear function of the user's step
// apex (longer steps for higher lifts). Built offline (legwork/wip/offline/learn.hpp); the lookup here is a
// multilinear interpolation: no allocation, no exceptions.
#include <legwork/core/types.hpp>
#include <legwork/wip/gait.hpp>

#include <array>

namespace legwork::wip {

struct LearnedMapping {
  static constexpr int kNodes = 13;  // grid nodes per cycle-coordinate axis over [0, 2]
  static constexpr int kSinceNodes = 5;  // grid nodes over the time since the last foot strike
  static constexpr std::array<double, kSinceNodes> kSince = {0.0, 0.15, 0.3, 0.6, 1.2};  // s (clamped beyond)
  static constexpr double kDefaultStridePeriod = 1.1;  // s, before two foot-offs of a foot were seen
  static constexpr double kMaxStridePeriod = 2.5;      // s: longer foot-off intervals are pauses, not strides
  // shape[lead][since][own][other]: the foot's depth divided by its walk's
  // depth amplitude (half the 5-95 % range) at the grid nodes; lead = 1 when
  // this foot landed last (it is the leading foot); since = the time since
  // that landing (standing pauses hold the feet closer than a fresh landing).
  std::array<double, 2 * kSinceNodes * kNodes * kNodes> shape{};
  // Depth amplitude / leg length = amplitude_intercept + amplitude_slope *
  // apex (the user's step apex estimate, m) + cadence_slope * cadence
  // (strides per second, 1 / the running stride period), clamped to the
  // training range: the step length follows the user's lift and stepping
  // rate (least squares over the walks).
  double amplitude_intercept = 0.4, amplitude_slope = 0, cadence_slope = 0;
  double amplitude_min = 0.2, amplitude_max = 0.6;
  // Turning: real steps shorten while the walker turns (turn-arounds, turns
  // on the spot), which the ankle heights do not show but the head's yaw
  // does. The depth is multiplied by turn_gain(turn rate) = turn_intercept +
  // turn_slope * min(rate, kMaxTurnRate), clamped to [0, kMaxTurnGain]; rate =
  // the head yaw's speed (rad/s) smoothed over kTurnTau (State::turn_rate).
  // Least squares over the training frames; 1 and 0 (no turn term) in tables
  // of format 1.
  static constexpr double kTurnTau = 1.2;          // s
  static constexpr double kMaxTurnRate = kPi;  // rad/s (180 deg/s)
  static constexpr double kMaxTurnGain = 2.0;  // the reader's message says 2
  double turn_intercept = 1.0, turn_slope = 0.0;
  double apex_mean = 0.12;   // m: mean step apex (gait machine estimate) of the training frames
  double cadence_mean = 0.9; // strides/s: mean cadence of the training frames
  int samples = 0;           // training frames (both feet)

  static std::size_t index(int lead, int since, int own, int other) {
    return static_cast<std::size_t>(((lead * kSinceNodes + since) * kNodes + own) * kNodes + other);
  }
  double& at(int lead, int since, int own, int other) { return shape[index(lead, since, own, other)]; }
  double at(int lead, int since, int own, int other) const { return shape[index(lead, since, own, other)]; }
  // The shape value for a foot at cycle coordinate `own` while the other
  // foot is at `other`, `since` s after the last foot strike; lead: 1 this
  // foot landed last, 0 the other did, -1 unknown (the mean of both).
  double lookup(double own, double other, int lead, double since) const;
  // Depth amplitude / leg length for the user's step apex (m) and cadence
  // (strides/s), clamped; non-finite inputs take the training means.
  double amplitude(double apex, double cadence) const;
  // The turning gain for a smoothed head-yaw rate (rad/s; non-finite = 0).
  double turn_gain(double turn_rate) const;
  // Depth / leg length: amplitude(apex, cadence) * lookup(own, other, lead, since) * turn_gain(turn_rate).
  double depth(double own, double other, int lead, double since, double apex, double cadence, double turn_rate) const {
    return amplitude(apex, cadence) * lookup(own, other, lead, since) * turn_gain(turn_rate);
  }
};

// Lower grid node and fraction (0..1 toward the next) of a cycle coordinate
// (clamped to [0, 2]; NaN = 0) and of a time since the last strike (clamped
// to kSince; NaN = the last node), as lookup() interpolates.
void locate_cycle(double c, int& node, double& fraction);
void locate_since(double since, int& node, double& fraction);

// The cycle coordinate of a foot from its gait machine and filtered height
// (metres above the floor): rising (double support, initial swing) h / the
// running apex estimate in [0, 1]; descending (mid, terminal swing) 2 - h /
// this swing's apex in [1, 2].
double cycle_coordinate(const GaitMachine& g, const GaitSettings& p, double h);

}  // namespace legwork::wip
