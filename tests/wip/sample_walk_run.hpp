#pragma once
// The method (default settings, rolling floor) run once over the sample walk
// 05_01's own ankles at 30 Hz, shared by the wip tests that need real frames;
// and the model of the sample skeleton.
#include <legwork/wip/offline/run.hpp>

#include "cmu_sample.hpp"

#include <vector>

namespace legwork::wip::samples {

// The method's model for the sample CMU skeleton (walking 07_01), built once.
inline const Model& cmu_model() {
  static const Model m = make_model(testdata::sample_skeleton());
  return m;
}

struct SampleWalkRun {
  double leg_length = 0;
  std::vector<Info> frames;
};

inline const SampleWalkRun& sample_walk_run() {
  static const SampleWalkRun run = [] {
    const Motion walk = testdata::load_sample("cmu/bvh/walking/05_01.bvh");
    const Model model = make_model(walk.skeleton);
    RunOptions ro;
    ro.calibrate = false;
    ro.keep_poses = false;
    return SampleWalkRun{model.leg_length(), run_wip(model, tracker_frames_from_motion(walk, 30), ro).frames};
  }();
  return run;
}

}  // namespace legwork::wip::samples
