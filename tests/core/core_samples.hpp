#pragma once
// What the core tests share: the sample walk they run on and a rotation
// distance that ignores the quaternion's sign.
#include <legwork/core/types.hpp>

#include "cmu_sample.hpp"

#include <cmath>

namespace legwork::testdata {

// The repo's sample walk, data/cmu walking 07_01 (metres, T-pose frame dropped).
inline Motion walk() { return load_sample("cmu/bvh/walking/07_01.bvh"); }

// 0 for the same rotation (q and -q alike), up to 1 for a half turn apart.
inline double quat_distance(const Quat& a, const Quat& b) { return 1.0 - std::abs(a.dot(b)); }

}  // namespace legwork::testdata
