// BVH parse throughput: legwork's reader against assimp's BVH importer on the
// same file in the same run (bytes/s -> MB/s in the report).
// In memory: legwork's parse_bvh on the text vs assimp's ReadFileFromMemory
// with hint "bvh"; from disk (page cache): read_bvh vs Importer::ReadFile.
// assimp 5.2.5's BVH loader keeps state between reads (a second read with the
// same Importer fails with "Unexpected end of file while trying to read a
// float"), so each iteration constructs a fresh Importer with the timer paused.
//   ./bvh_bench --benchmark_out=bvh.json --benchmark_out_format=json
#include <legwork/io/bvh.hpp>
#include <legwork/io/text.hpp>

#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <string>

namespace {

namespace fs = std::filesystem;

// The repo sample (always present) and the largest shared CMU trial (when present).
struct Input {
  std::string name, path;
};
std::vector<Input> inputs() {
  std::vector<Input> out = {{"05_01", std::string(LEGWORK_SOURCE_DIR) + "/data/cmu/bvh/walking/05_01.bvh"}};
  const fs::path shared = fs::path(LEGWORK_SOURCE_DIR).parent_path() / "shared/data/cmu/bvh/boxing/14_02.bvh";
  if (fs::exists(shared)) out.push_back({"14_02", shared.string()});
  return out;
}

void BM_LegworkParseBvh(benchmark::State& state, const std::string& path) {
  const std::string text = legwork::io::read_text_file(path);
  for (auto _ : state) {
    auto f = legwork::io::parse_bvh(text, path);
    benchmark::DoNotOptimize(f.motion.all_rotations().data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(text.size()));
}

void BM_LegworkReadBvh(benchmark::State& state, const std::string& path) {
  const auto bytes = static_cast<int64_t>(fs::file_size(path));
  for (auto _ : state) {
    auto f = legwork::io::read_bvh(path);
    benchmark::DoNotOptimize(f.motion.all_rotations().data());
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * bytes);
}

// Times read(importer) with a fresh importer per iteration; building and
// destroying the importer stays outside the timing.
template <class Read>
void time_assimp(benchmark::State& state, Read&& read) {
  for (auto _ : state) {
    state.PauseTiming();
    auto importer = std::make_unique<Assimp::Importer>();
    state.ResumeTiming();
    const aiScene* scene = read(*importer);
    if (!scene || scene->mNumAnimations == 0) {
      state.SkipWithError(importer->GetErrorString());
      break;
    }
    benchmark::DoNotOptimize(scene);
    state.PauseTiming();
    importer.reset();
    state.ResumeTiming();
  }
}

void BM_AssimpParseBvh(benchmark::State& state, const std::string& path) {
  const std::string text = legwork::io::read_text_file(path);
  time_assimp(state, [&](Assimp::Importer& importer) { return importer.ReadFileFromMemory(text.data(), text.size(), 0, "bvh"); });
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(text.size()));
}

void BM_AssimpReadBvh(benchmark::State& state, const std::string& path) {
  const auto bytes = static_cast<int64_t>(fs::file_size(path));
  time_assimp(state, [&](Assimp::Importer& importer) { return importer.ReadFile(path, 0); });
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * bytes);
}

const bool registered = [] {
  for (const auto& in : inputs()) {
    benchmark::RegisterBenchmark(("BM_LegworkParseBvh/" + in.name).c_str(), BM_LegworkParseBvh, in.path)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_AssimpParseBvh/" + in.name).c_str(), BM_AssimpParseBvh, in.path)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_LegworkReadBvh/" + in.name).c_str(), BM_LegworkReadBvh, in.path)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_AssimpReadBvh/" + in.name).c_str(), BM_AssimpReadBvh, in.path)->Unit(benchmark::kMillisecond);
  }
  return true;
}();

}  // namespace

BENCHMARK_MAIN();
