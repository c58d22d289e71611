#pragma once
// A walking-in-place depth mapping learned from real walking (issue 13, item
// 3), beside the document's equations 1-4. Each foot's gait state is reduced
// to a cycle coordinate c in [0, 2] (0 at rest, h / apex while rising, 2 - h /
// apex while descending); a table over (own c, other foot's c, which foot
// landed last) gives the foot's fore-aft offset from the pelvis divided by the
// leg length, averaged over real CMU walks run through the same filters and
// gait machines (so their lag is learned too). A gain learned from the same
// walks scales the depth with the user's step apex (longer steps for higher
// lifts). Built offline (legwork/wip/offline/learn.hpp); the lookup here is a
// bilinear interpolation: no allocation, no exceptions.
#include <legwork/wip/gait.hpp>

#include <array>

namespace legwork::wip {

struct LearnedMapping {
  static constexpr int kNodes = 21;  // grid nodes per cycle-coordinate axis over [0, 2]
  // depth[lead][own][other]: z / leg length at the grid nodes; lead = 1 when
  // this foot landed last (it is the leading foot).
  std::array<double, 2 * kNodes * kNodes> depth{};
  double apex_mean = 0.12;   // m: mean step apex (gait machine estimate) of the training walks
  double gain_slope = 0;     // depth gain per metre of apex above apex_mean (learned; 0 = none)
  double gain_min = 0.6, gain_max = 1.6;  // the gain is clamped to this range
  int samples = 0;           // training frames (both feet)

  double& at(int lead, int own, int other) { return depth[static_cast<std::size_t>((lead * kNodes + own) * kNodes + other)]; }
  double at(int lead, int own, int other) const {
    return depth[static_cast<std::size_t>((lead * kNodes + own) * kNodes + other)];
  }
  // z / leg length for a foot at cycle coordinate `own` while the other foot
  // is at `other`; lead: 1 this foot landed last, 0 the other did, -1 unknown
  // (the mean of both).
  double lookup(double own, double other, int lead) const;
  // Depth gain for the user's step apex (m), clamped.
  double gain(double apex) const;
};

// The cycle coordinate of a foot from its gait machine and filtered height
// (metres above the floor): rising (double support, initial swing) h / the
// running apex estimate in [0, 1]; descending (mid, terminal swing) 2 - h /
// this swing's apex in [1, 2].
double cycle_coordinate(const GaitMachine& g, const GaitSettings& p, double h);

}  // namespace legwork::wip
