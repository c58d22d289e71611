// Renderer throughput on a real CMU walk: one stick-figure PNG (draw + PNG
// encode), one SVG, and a 9-pose contact sheet. Figures in ms per picture.
#include <legwork/io/bvh.hpp>
#include <legwork/render/render.hpp>

#include <benchmark/benchmark.h>

#include "cmu_sample.hpp"

#include <filesystem>
#include <string>

using namespace legwork;

namespace {
const Motion& walk() {
  static const Motion m = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  return m;
}
std::string tmp(const char* name) { return (std::filesystem::temp_directory_path() / name).string(); }

void BM_FramePng640x480(benchmark::State& state) {
  const Motion& m = walk();
  render::Camera cam;
  cam.view = render::View::ThreeQuarter;
  int f = 0;
  for (auto _ : state) {
    render::Scene s;
    s.figures.push_back(render::make_figure(m.skeleton, m.frame(f)));
    render::render_scene(s, cam, tmp("legwork_bench_frame.png"));
    f = (f + 7) % m.frame_count();
  }
}
BENCHMARK(BM_FramePng640x480)->Unit(benchmark::kMillisecond);

void BM_FrameSvg(benchmark::State& state) {
  const Motion& m = walk();
  render::Camera cam;
  for (auto _ : state) {
    render::Scene s;
    s.figures.push_back(render::make_figure(m.skeleton, m.frame(100)));
    render::render_scene(s, cam, tmp("legwork_bench_frame.svg"));
  }
}
BENCHMARK(BM_FrameSvg)->Unit(benchmark::kMillisecond);

void BM_ContactSheet9Poses(benchmark::State& state) {
  const Motion& m = walk();
  std::vector<Pose> poses;
  for (int f = 0; f < 9; ++f) {
    const auto fr = m.frame(f * 30);
    Pose p;
    p.rotations.assign(fr.rotations.begin(), fr.rotations.end());
    p.translations.assign(fr.translations.begin(), fr.translations.end());
    poses.push_back(p);
  }
  render::SheetOptions opt;
  for (auto _ : state) render::render_contact_sheet(m.skeleton, poses, opt, tmp("legwork_bench_sheet.png"));
}
BENCHMARK(BM_ContactSheet9Poses)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
