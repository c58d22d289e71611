// Walking-in-place runtime cost: one avatar's per-frame update (signal
// processing, gait machines, equations, speed, FK and two-bone IK for both
// legs), driven by a real CMU walk's ankles, and the same without a pose (no
// FK or IK: the evaluation's runs); and one two-bone IK solve.
// Counters: avatars_per_core_30Hz = how many avatars one core updates at 30 Hz.
#include <benchmark/benchmark.h>

#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/wip/offline/learn.hpp>
#include <legwork/wip/offline/synthetic.hpp>
#include <legwork/wip/wip.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <string>
#include <vector>

namespace {

using namespace legwork;
using namespace legwork::wip;

Motion load_walk(const char* name) { return testdata::load_sample(std::string("cmu/bvh/walking/") + name); }

// Feeds the 30 Hz samples to update() once per iteration and reports how
// many avatars one core keeps up with.
// With `solve_legs` false, update() gets an empty pose (the evaluation's and
// the tuning's runs): the gait and the IK targets without the legs' FK and IK.
void run_updates(benchmark::State& state, const Model& model, const std::vector<TrackerFrame>& samples, bool solve_legs = true) {
  State st(model);
  Pose pose = solve_legs ? Pose(model.skeleton()) : Pose();
  Info info;
  std::size_t i = 0;
  double offset = 0;
  const double period = samples.back().time + 1.0 / 30;
  for (auto _ : state) {
    TrackerFrame s = samples[i];
    s.time += offset;  // loop the clip with time still increasing
    benchmark::DoNotOptimize(update(model, s, st, pose.ref(), &info));
    if (++i == samples.size()) i = 0, offset += period;
  }
  state.counters["avatars_per_core_30Hz"] =
      benchmark::Counter(static_cast<double>(state.iterations()) / 30.0, benchmark::Counter::kIsRate);
}

void BM_WipUpdatePerAvatarFrame(benchmark::State& state) {
  const Motion walk = load_walk("16_15.bvh");
  const Model model = make_model(walk.skeleton);
  const auto samples = tracker_frames_from_motion(walk, 30.0);
  run_updates(state, model, samples);
  state.counters["joints"] = model.skeleton().joint_count();
}
BENCHMARK(BM_WipUpdatePerAvatarFrame);

// The same frames without a pose: what `wip eval` and `wip tune` pay per frame.
void BM_WipUpdateWithoutPose(benchmark::State& state) {
  const Motion walk = load_walk("16_15.bvh");
  const Model model = make_model(walk.skeleton);
  run_updates(state, model, tracker_frames_from_motion(walk, 30.0), false);
}
BENCHMARK(BM_WipUpdateWithoutPose);

// The same with the depth mapping learned from real walks (the shipped table).
void BM_WipUpdateLearnedMapping(benchmark::State& state) {
  const Motion walk = load_walk("16_15.bvh");
  Settings settings;
  settings.mapping.depth = DepthMapping::Learned;
  const LearnedMapping table = read_learned_mapping(testdata::sample("wip/learned_mapping.txt").string());
  const Model model = make_model(walk.skeleton, settings, {}, &table);
  run_updates(state, model, tracker_frames_from_motion(walk, 30.0));
}
BENCHMARK(BM_WipUpdateLearnedMapping);

void BM_WipUpdateSynthetic(benchmark::State& state) {
  const Model model = make_model(load_walk("07_01.bvh").skeleton);
  const auto samples = synthetic_stepping({}).frames;
  run_updates(state, model, samples);
}
BENCHMARK(BM_WipUpdateSynthetic);

void BM_TwoBoneIkSolve(benchmark::State& state) {
  const Motion walk = load_walk("07_01.bvh");
  const Skeleton& s = walk.skeleton;
  const auto leg = ik::left_leg(s);
  Pose pose(s);
  std::vector<Transform> model(static_cast<std::size_t>(s.joint_count()));
  forward_kinematics(s, pose, model);
  const Vec3 hip = model[static_cast<std::size_t>(leg.root)].translation;
  double phase = 0;
  for (auto _ : state) {
    ik::TwoBoneTarget t;
    t.position = hip + Vec3(0.02, -0.7 + 0.05 * std::sin(phase), 0.2 * std::cos(phase));
    t.hint = hip + Vec3(0, -0.35, 0.3);
    ik::solve_two_bone(s, leg, t, pose.ref(), model);
    benchmark::DoNotOptimize(model.data());
    phase += 0.1;
  }
}
BENCHMARK(BM_TwoBoneIkSolve);

}  // namespace

BENCHMARK_MAIN();
