#pragma once
// Shared helpers of the walkcycle tests: the shipped walks on the CMU
// skeleton, a quarter-turn path, error capture.
#include <legwork/walkcycle/cycle.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/path.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "cmu_sample.hpp"

namespace legwork::walkcycle::samples {

inline const Skeleton& cmu_skeleton() { return testdata::sample_skeleton(); }

inline std::string walk_file(const std::string& name) { return testdata::walk_keys_file(name); }

inline const std::vector<std::string> kWalks{"normal", "sneak", "double-bounce"};

inline CycleModel shipped(const std::string& name) {
  return build_cycle(cmu_skeleton(), read_walk_keys(walk_file(name), cmu_skeleton()));
}

// A 90-degree left turn: straight 2 m, a quarter circle of radius 3 m, straight 2 m.
inline Path quarter_turn() {
  return parse_path_json(R"({"bezier": [[0,0],[0,0.7],[0,1.3],[0,2],
                                        [0,3.657],[1.343,5],[3,5],
                                        [3.7,5],[4.3,5],[5,5]]})",
                         "quarter-turn");
}

inline double rotation_distance(const Quat& a, const Quat& b) { return 1.0 - std::abs(a.coeffs().dot(b.coeffs())); }

inline std::string expect_error(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected legwork::Error";
  return "";
}

}  // namespace legwork::walkcycle::samples
