// Walk cycles cut from real walking for the key-frame baseline.
#include <legwork/wip/baseline.hpp>
#include <legwork/wip/offline/run.hpp>
#include <legwork/wip/offline/walk_cycle.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <algorithm>
#include <cmath>

namespace legwork::wip {
namespace {

Motion load(const std::string& rel) { return testdata::load_sample(rel); }

TEST(RealWalking, WalkCycleIsInPlaceAndLoops) {
  const Motion cycle = extract_walk_cycle(load("cmu/bvh/walking/07_01.bvh"));
  EXPECT_GT(cycle.duration(), 0.7);
  EXPECT_LT(cycle.duration(), 1.8);
  double max_xz = 0;
  for (int f = 0; f < cycle.frame_count(); ++f) {
    const Vec3 r = cycle.frame(f).translations[0];
    max_xz = std::max(max_xz, std::hypot(r.x(), r.z()));
  }
  EXPECT_LT(max_xz, 0.15);
  // The feet swing fore and aft about the pelvis in opposite phase.
  const auto zl = ankle_depths(cycle, kLeft), zr = ankle_depths(cycle, kRight);
  const auto [lo, hi] = std::minmax_element(zl.begin(), zl.end());
  EXPECT_GT(*hi - *lo, 0.4);
  double dot = 0;
  for (std::size_t i = 0; i < zl.size(); ++i) dot += zl[i] * zr[i];
  EXPECT_LT(dot, 0);
}

TEST(KeyframeBaseline, FollowsTheWalkingDecisions) {
  const Motion cycle = extract_walk_cycle(load("cmu/bvh/walking/07_01.bvh"));
  const Model model = make_model(testdata::sample_skeleton());
  std::vector<Info> frames(90);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    frames[i].time = static_cast<double>(i) / 30;
    frames[i].walking = i >= 30 && i < 60;
  }
  Motion avatar(model.skeleton(), 30, static_cast<int>(frames.size()));
  const auto run = run_keyframe_baseline(model, cycle, frames, 30.0, &avatar);
  ASSERT_EQ(run.z[0].size(), frames.size());
  EXPECT_EQ(run.z[0][10], 0.0);  // idle before walking
  double moving = 0;
  for (std::size_t i = 35; i < 60; ++i) moving = std::max(moving, std::abs(run.z[0][i]));
  EXPECT_GT(moving, 0.1);
}

}  // namespace
}  // namespace legwork::wip
