#pragma once
// Pose checks shared by the runtime tests: every rotation and translation
// finite; two poses bit for bit the same (a Rejected frame leaves the pose alone).
#include <legwork/core/motion.hpp>

namespace legwork::testdata {

inline bool finite_pose(const Pose& p) {
  for (std::size_t j = 0; j < p.rotations.size(); ++j)
    if (!p.rotations[j].coeffs().allFinite() || !p.translations[j].allFinite()) return false;
  return true;
}

inline bool same_pose(const Pose& a, const Pose& b) {
  for (std::size_t j = 0; j < a.rotations.size(); ++j)
    if (a.rotations[j].coeffs() != b.rotations[j].coeffs() || a.translations[j] != b.translations[j]) return false;
  return true;
}

}  // namespace legwork::testdata
