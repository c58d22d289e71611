// Full-body IK avatar (ik::update) per-frame cost on a real CMU walk at 90 Hz (head and
// hands from the capture). Figures: ns per frame; frames/s as a counter.
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/ik/full_body.hpp>
#include <legwork/io/bvh.hpp>

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

using namespace legwork;

namespace {
struct Input {
  Motion motion;
  std::vector<TrackerFrame> frames;
};
const Input& walk90() {
  static const Input in = [] {
    Input x;
    x.motion = resample(
        io::load_bvh(std::string(LEGWORK_SOURCE_DIR) + "/data/cmu/bvh/walking/07_01.bvh", {.drop_first_frame = true}),
        90.0);
    const Skeleton& s = x.motion.skeleton;
    std::vector<Transform> g(static_cast<std::size_t>(s.joint_count()));
    for (int f = 0; f < x.motion.frame_count(); ++f) {
      forward_kinematics(s, x.motion.frame(f), g);
      const auto at = [&](Role r) { return g[static_cast<std::size_t>(s.roles[r])]; };
      TrackerFrame t;
      t.head() = {at(Role::Head).translation, at(Role::Head).rotation, true};
      t.hand(kLeft) = {at(Role::LeftHand).translation, at(Role::LeftHand).rotation, true};
      t.hand(kRight) = {at(Role::RightHand).translation, at(Role::RightHand).rotation, true};
      x.frames.push_back(t);
    }
    return x;
  }();
  return in;
}

void BM_FullBodyIkFrame(benchmark::State& state) {
  const Input& in = walk90();
  const ik::Model model = ik::make_model(in.motion.skeleton);
  ik::State st(model);
  Pose pose(model.skeleton());
  std::size_t f = 0;
  double time = 0;
  for (auto _ : state) {
    TrackerFrame frame = in.frames[f];  // the clip looped, time always increasing
    frame.time = time;
    time += 1.0 / 90.0;
    ik::update(model, frame, st, pose.ref());
    benchmark::DoNotOptimize(pose.rotations.data());
    if (++f == in.frames.size()) f = 0;
  }
  state.counters["frames_per_second"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FullBodyIkFrame)->Unit(benchmark::kMicrosecond);
}  // namespace

BENCHMARK_MAIN();
