// GLB import: legwork's own files come back exactly (BVH -> GLB -> BVH on
// real CMU clips at 120 and 60 Hz), other tools' skins and animations are
// read when the rig resolves to roles (assets built here with tinygltf).
#include <tiny_gltf.h>

#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

using namespace legwork;

namespace {

std::string temp(const std::string& name) { return (std::filesystem::temp_directory_path() / name).string(); }

// The numbers of a BVH text's MOTION section after the Frame Time line.
std::vector<double> motion_numbers(const std::string& text) {
  const auto at = text.find("Frame Time:");
  std::istringstream in(text.substr(text.find('\n', at) + 1));
  std::vector<double> out;
  for (double v; in >> v;) out.push_back(v);
  return out;
}

std::string frame_time_line(const std::string& text) {
  const auto at = text.find("Frame Time:");
  return text.substr(at, text.find('\n', at) - at);
}

// BVH file -> GLB -> Motion -> BVH text in the file's own units and channel layout.
struct RoundTrip {
  io::BvhFile original;
  Motion back;
  std::string bvh_text;
};

RoundTrip bvh_glb_bvh(const std::filesystem::path& bvh, bool exact_copy) {
  RoundTrip r;
  r.original = io::read_bvh(bvh.string());
  const std::string glb = temp("legwork_rt_" + bvh.stem().string() + ".glb");
  io::GltfOptions opt;
  opt.exact_copy = exact_copy;
  io::write_glb(glb, r.original.motion, opt);
  r.back = io::read_glb(glb);
  std::filesystem::remove(glb);
  io::BvhWriteOptions w;
  w.scale = 1.0 / r.original.report.scale;
  w.channels = r.original.channels;
  if (exact_copy) r.bvh_text = io::format_bvh(r.back, w);
  return r;
}

// Frames, frame time and every channel value equal to 1e-6.
void expect_exact_round_trip(const std::filesystem::path& bvh) {
  SCOPED_TRACE(bvh.string());
  const RoundTrip r = bvh_glb_bvh(bvh, true);
  const std::string text = io::read_text_file(bvh.string());
  ASSERT_EQ(r.back.frame_count(), r.original.motion.frame_count());
  EXPECT_NEAR(r.back.frame_time(), r.original.motion.frame_time(), 1e-12);
  EXPECT_NEAR(std::stod(frame_time_line(r.bvh_text).substr(11)), std::stod(frame_time_line(text).substr(11)), 1e-6);
  const auto a = motion_numbers(text);
  const auto b = motion_numbers(r.bvh_text);
  ASSERT_EQ(a.size(), b.size());
  // Which numbers of a frame are angles (-180 and 180 degrees are one angle).
  std::vector<bool> angle;
  for (const auto& joint : r.original.channels)
    for (io::Channel c : joint.channels) angle.push_back(c >= io::Channel::Xrotation);
  ASSERT_EQ(a.size() % angle.size(), 0u);
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = std::abs(a[i] - b[i]);
    worst = std::max(worst, angle[i % angle.size()] ? std::min(d, std::abs(d - 360)) : d);
  }
  EXPECT_LE(worst, 1e-6) << "worst channel difference (file units / degrees)";
}

}  // namespace

TEST(GltfReader, BvhGlbBvhIsExactOnSampleClipsAt120And60Hz) {
  expect_exact_round_trip(testdata::sample("cmu/bvh/walking/07_01.bvh"));   // 120 Hz, 317 frames
  expect_exact_round_trip(testdata::sample("cmu/bvh/swimming/79_02.bvh"));  // 60 Hz
  expect_exact_round_trip(testdata::sample("cmu/bvh_daz/climbing_ladder/14_33.bvh"));  // DAZ layout
}

TEST(GltfReader, BvhGlbBvhIsExactOnSharedClips) {
  LEGWORK_REQUIRE_SHARED_CMU();
  // The first two trials at each frame time in the manifest.
  std::ifstream manifest(testdata::shared_cmu() / "MANIFEST.tsv");
  std::string line;
  std::getline(manifest, line);
  std::map<std::string, int> taken;
  while (std::getline(manifest, line)) {
    std::istringstream cols(line);
    std::vector<std::string> f;
    for (std::string c; std::getline(cols, c, '\t');) f.push_back(c);
    if (f.size() < 6 || taken[f[5]] >= 2) continue;
    ++taken[f[5]];
    expect_exact_round_trip(testdata::shared_cmu() / f[0]);
  }
  EXPECT_GE(taken[".0166667"], 1) << "no 60 Hz clip in the manifest";
  EXPECT_GE(taken[".0083333"], 1) << "no 120 Hz clip in the manifest";
}

TEST(GltfReader, FloatChannelsAloneKeepFramesAndRate) {
  // What another tool sees (no exact copy): one frame per key, the rate
  // written, values within float rounding.
  for (const char* clip : {"cmu/bvh/walking/07_01.bvh", "cmu/bvh/swimming/79_02.bvh"}) {
    SCOPED_TRACE(clip);
    const RoundTrip r = bvh_glb_bvh(testdata::sample(clip), false);
    ASSERT_EQ(r.back.frame_count(), r.original.motion.frame_count());
    EXPECT_NEAR(r.back.frame_time(), r.original.motion.frame_time(), 1e-12);
    const auto a = joint_positions(r.original.motion);
    const auto b = joint_positions(r.back);
    double worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
    EXPECT_LT(worst, 1e-5) << "worst joint position difference (m)";
  }
}
