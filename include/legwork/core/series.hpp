#pragma once
// Small offline helpers over sampled signals (used to find floors and contacts
// in motion capture). They allocate; not for per-frame runtime code.
#include <vector>

namespace legwork {

// Rolling minimum over a window of +-w samples around each sample (O(n));
// throws legwork::Error for w < 0.
std::vector<double> rolling_min(const std::vector<double>& x, int w);

}  // namespace legwork
