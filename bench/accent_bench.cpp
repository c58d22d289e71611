// Accentuation engine figures (Google Benchmark): per-frame update() of one
// avatar driven by a real held-out trial, per search mode; database load by
// mmap; database build. Uses the full shared CMU set (every class, one running
// trial held out) when ../shared/data/cmu exists, else the repo's sample data.
#include <legwork/accent/accent.hpp>
#include <legwork/accent/offline/builder.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/io/bvh.hpp>

#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <string>

using namespace legwork;
using namespace legwork::accent;
namespace fs = std::filesystem;

namespace {

struct Setup {
  std::string data;
  std::vector<TrialInput> trials;
  Database db;
  std::vector<TrackerFrame> frames;
  double height = 0;
  std::string path;
};

Setup& setup() {
  static Setup s = [] {
    Setup x;
    const fs::path shared = fs::path(LEGWORK_SOURCE_DIR).parent_path() / "shared" / "data" / "cmu";
    const bool full = fs::exists(shared / "MANIFEST.tsv");
    x.data = full ? shared.string() : std::string(LEGWORK_SOURCE_DIR) + "/data/cmu";
    const std::string held = full ? "bvh/running/35_26.bvh" : "bvh/walking/07_02.bvh";
    std::fprintf(stderr, "accent_bench: database from %s (all classes, %s held out)\n", x.data.c_str(), held.c_str());
    x.trials = load_trials(x.data, {}, {held});
    x.db = build_database(x.trials, BuildConfig{});
    x.db.build_index();
    io::BvhReadOptions opt;
    opt.drop_first_frame = true;
    const Motion input = resample(io::load_bvh(x.data + "/" + held, opt), 90.0);
    x.frames = tracker_frames_from_motion(input);
    x.height = measure_body(input.skeleton).standing_height;
    x.path = (fs::temp_directory_path() / "legwork_accent_bench.lwdb").string();
    save_database(x.path, x.db);
    return x;
  }();
  return s;
}

void update_loop(benchmark::State& state, SearchMode mode, Settings cfg = {}) {
  Setup& s = setup();
  cfg.search = mode;
  cfg.user_height = s.height;
  const Model model = make_model(s.db, cfg);
  State avatar(model);
  Pose pose(model.skeleton());
  std::size_t f = 0;
  double t = 0;
  for (auto _ : state) {
    TrackerFrame in = s.frames[f];
    in.time = t;  // the trial loops; time keeps increasing
    benchmark::DoNotOptimize(update(model, in, avatar, pose.ref()));
    t += 1.0 / 90.0;
    if (++f == s.frames.size()) {
      // Replay the trial as a new session (a wrap-around would feed a jump).
      state.PauseTiming();
      reset(model, avatar);
      f = 0;
      state.ResumeTiming();
    }
  }
  state.counters["frames_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["windows"] = s.db.window_count();
}

void BM_UpdateBruteForce(benchmark::State& state) { update_loop(state, SearchMode::BruteForce); }
void BM_UpdateExact(benchmark::State& state) { update_loop(state, SearchMode::Exact); }
void BM_UpdateFast(benchmark::State& state) { update_loop(state, SearchMode::Fast); }
BENCHMARK(BM_UpdateBruteForce)->Unit(benchmark::kMicrosecond)->MeasureProcessCPUTime();
BENCHMARK(BM_UpdateExact)->Unit(benchmark::kMicrosecond)->MeasureProcessCPUTime();
BENCHMARK(BM_UpdateFast)->Unit(benchmark::kMicrosecond)->MeasureProcessCPUTime();
// The paper's settings: k = 5, no hand IK, EWMA smoothing only.
void BM_UpdateFastPaper(benchmark::State& state) {
  Settings cfg;
  cfg.k_left = cfg.k_right = 5;
  cfg.hand_ik = 0;
  cfg.smooth_halflife = 0;
  update_loop(state, SearchMode::Fast, cfg);
}
// Default with another k (what k costs).
void BM_UpdateFastK(benchmark::State& state) {
  Settings cfg;
  cfg.k_left = cfg.k_right = static_cast<int>(state.range(0));
  update_loop(state, SearchMode::Fast, cfg);
}
BENCHMARK(BM_UpdateFastPaper)->Unit(benchmark::kMicrosecond)->MeasureProcessCPUTime();
BENCHMARK(BM_UpdateFastK)->Arg(5)->Arg(8)->Arg(10)->Unit(benchmark::kMicrosecond)->MeasureProcessCPUTime();

void BM_LoadMmap(benchmark::State& state) {
  Setup& s = setup();
  LoadOptions opt;
  opt.build_index = false;
  opt.verify_checksum = state.range(0) != 0;
  for (auto _ : state) benchmark::DoNotOptimize(load_database(s.path, opt).window_count());
  state.counters["bytes"] = static_cast<double>(s.db.bytes().size());
}
BENCHMARK(BM_LoadMmap)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_BuildIndex(benchmark::State& state) {
  Setup& s = setup();
  for (auto _ : state) s.db.build_index();
}
BENCHMARK(BM_BuildIndex)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_BuildDatabase(benchmark::State& state) {
  Setup& s = setup();
  for (auto _ : state) benchmark::DoNotOptimize(build_database(s.trials, BuildConfig{}).window_count());
}
BENCHMARK(BM_BuildDatabase)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
