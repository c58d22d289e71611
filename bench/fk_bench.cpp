// Forward kinematics throughput in joint transforms per second (one core),
// over every frame of a real CMU trial.
//   ./fk_bench --benchmark_out=fk.json --benchmark_out_format=json
#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>

#include <benchmark/benchmark.h>

#include "cmu_sample.hpp"

namespace {

const legwork::Motion& walk() {
  static const legwork::Motion m = legwork::testdata::load_sample("cmu/bvh/walking/05_01.bvh");
  return m;
}

// Full transforms (rotation + translation) for every joint of every frame.
void BM_ForwardKinematics(benchmark::State& state) {
  const auto& m = walk();
  std::vector<legwork::Transform> out(static_cast<std::size_t>(m.frame_count() * m.joint_count()));
  for (auto _ : state) {
    legwork::forward_kinematics(m, out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * m.frame_count() * m.joint_count());
}
BENCHMARK(BM_ForwardKinematics)->Unit(benchmark::kMicrosecond);

// Positions only.
void BM_ForwardPositions(benchmark::State& state) {
  const auto& m = walk();
  std::vector<legwork::Vec3> out(static_cast<std::size_t>(m.frame_count() * m.joint_count()));
  for (auto _ : state) {
    legwork::forward_positions(m, out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * m.frame_count() * m.joint_count());
}
BENCHMARK(BM_ForwardPositions)->Unit(benchmark::kMicrosecond);

// One pose at a time (the per-frame runtime case: the pose stays in cache).
void BM_ForwardKinematicsOnePose(benchmark::State& state) {
  const auto& m = walk();
  std::vector<legwork::Transform> out(static_cast<std::size_t>(m.joint_count()));
  int f = 0;
  for (auto _ : state) {
    legwork::forward_kinematics(m.skeleton, m.frame(f), out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
    f = (f + 1) % m.frame_count();
  }
  state.SetItemsProcessed(state.iterations() * m.joint_count());
}
BENCHMARK(BM_ForwardKinematicsOnePose);

}  // namespace

BENCHMARK_MAIN();
