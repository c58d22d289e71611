#pragma once
// The repo's sample CMU trials (data/cmu), loaded the way every test and
// benchmark reads them: T-pose frame dropped, units in metres. Free of gtest
// so that benchmarks (which have tests/ on their include path) use it too.
#include <legwork/io/bvh.hpp>

#include <string>

namespace legwork::testdata {

// A trial under the repo's data/ (as testdata::sample), e.g. "cmu/bvh/walking/07_01.bvh".
inline Motion load_sample(const std::string& rel) {
  io::BvhReadOptions o;
  o.drop_first_frame = true;
  return io::load_bvh(std::string(LEGWORK_SOURCE_DIR) + "/data/" + rel, o);
}

// The CMU skeleton of walking/07_01, loaded once.
inline const Skeleton& sample_skeleton() {
  static const Skeleton s = load_sample("cmu/bvh/walking/07_01.bvh").skeleton;
  return s;
}

// A shipped walk's key-pose file: data/walks/<name>.json.
inline std::string walk_keys_file(const std::string& name) {
  return std::string(LEGWORK_SOURCE_DIR) + "/data/walks/" + name + ".json";
}

}  // namespace legwork::testdata
