#pragma once
// Ground-truth gait events from motion capture (for evaluation and for
// cutting walk cycles out of walking trials). Offline: allocates, throws.
#include <legwork/core/motion.hpp>
#include <legwork/wip/offline/synthetic.hpp>

#include <vector>

namespace legwork::wip {

// Ground-truth contact: a foot is down when its ankle (heel) or toe is within
// `height_tol` of its local floor (rolling minimum over +-floor_window) and
// moving slower than `speed_tol`. Foot-off = the toe leaves, foot-strike =
// the first contact again.
struct TruthOptions {
  double height_tol = 0.03;   // m
  double speed_tol = 0.5;     // m/s
  double floor_window = 1.0;  // s each side
  double min_swing = 0.15;    // s: shorter lifts are not steps
  double min_stance = 0.05;   // s: shorter touch-downs do not split a swing
};
std::vector<SwingEvent> true_swings(const Motion& m, const TruthOptions& p = {});

}  // namespace legwork::wip
