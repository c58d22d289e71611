// Walk-cycle generator speed: building a cycle, sampling it, and generating a
// 100-step walk along a curved path (target <= 5 ms, file output excluded).
#include <benchmark/benchmark.h>

#include <legwork/io/bvh.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/measure.hpp>
#include <legwork/walkcycle/walker.hpp>

#include "cmu_sample.hpp"

#include <cstdio>
#include <string>

using namespace legwork;
using namespace legwork::walkcycle;

namespace {

const Skeleton& skeleton() { return testdata::sample_skeleton(); }

const WalkKeys& keys() {
  static const WalkKeys k = read_walk_keys(testdata::walk_keys_file("normal"), skeleton());
  return k;
}

// A long winding path: Catmull-Rom through points zig-zagging every 6 m,
// long enough for 100 steps of the normal walk.
Path winding_path(double length) {
  std::string pts;
  for (int i = 0; i * 6.0 <= length + 6; ++i)
    pts += (i ? "," : "") + std::string("[") + (i % 2 ? "2.5" : "-2.5") + "," + std::to_string(i * 6.0) + "]";
  return parse_path_json("{\"catmull_rom\": [" + pts + "]}", "bench");
}

void BM_BuildCycle(benchmark::State& st) {
  for (auto _ : st) benchmark::DoNotOptimize(build_cycle(skeleton(), keys()));
}
BENCHMARK(BM_BuildCycle)->Unit(benchmark::kMicrosecond);

void BM_SampleCycle(benchmark::State& st) {
  const CycleModel m = build_cycle(skeleton(), keys());
  Pose p(skeleton());
  double t = 0;
  for (auto _ : st) {
    sample_cycle(m, t, p.ref());
    t += 0.37;
    benchmark::DoNotOptimize(p.rotations.data());
  }
}
BENCHMARK(BM_SampleCycle);

// Arg 0: the smooth root (default: root averaged, legs by IK); 1: document 001's pivoting root;
// 2: the smooth root written at 30 fps (the walk's own rate is 24: its output frames then fall
// on cycle times that do not repeat to the bit, so each frame samples the cycle afresh).
void BM_Walk100StepsCurved(benchmark::State& st) {
  const CycleModel m = build_cycle(skeleton(), keys());
  const Path path = winding_path(200.0);
  WalkOptions o;
  o.steps = 100;  // exactly 100 steps (then the stop step)
  o.root = st.range(0) == 1 ? RootMotion::Pivot : RootMotion::Smooth;
  if (st.range(0) == 2) o.fps = 30;
  int frames = 0;
  double turning = 0;
  for (auto _ : st) {
    const WalkResult w = walk_path(m, path, o);
    frames = w.motion.frame_count();
    turning = w.turning_abs;
    benchmark::DoNotOptimize(w.motion.all_rotations().data());
  }
  st.counters["frames"] = frames;
  st.counters["total_turning_deg"] = rad2deg(turning);
}
BENCHMARK(BM_Walk100StepsCurved)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// One character steered live: one walkcycle::update per frame at 30 Hz,
// the heading asked for as the head's yaw. Arg 0: the smooth root (default:
// legs by IK); 1: document 001's pivoting root.
void BM_WalkerUpdate(benchmark::State& st) {
  Settings settings;
  settings.root = st.range(0) == 1 ? RootMotion::Pivot : RootMotion::Smooth;
  const Model model = make_model(build_cycle(skeleton(), keys()), settings);
  State s(model);
  Pose p(model.skeleton());
  TrackerFrame frame;
  frame.head().valid = true;
  double desired = 0;
  for (auto _ : st) {
    desired += 0.001;
    frame.time += 1.0 / 30.0;
    frame.head().rotation = Quat(Eigen::AngleAxisd(desired, Vec3::UnitY()));
    update(model, frame, s, p.ref());
    benchmark::DoNotOptimize(p.translations.data());
  }
}
BENCHMARK(BM_WalkerUpdate)->Arg(0)->Arg(1);

}  // namespace

BENCHMARK_MAIN();
