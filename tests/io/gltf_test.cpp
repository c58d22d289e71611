// GLB export: write_glb -> read_glb gives back the skeleton and the motion.
#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>

#include <unistd.h>

using namespace legwork;

namespace {
// Per process: ctest runs each test in its own process, two at a time, and a
// file shared between them was read while another test rewrote it (CI, session 10).
std::string gltf_temp(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name)).string();
}

// Keep the test fast: the first `frames` real frames.
Motion first_frames(const Motion& m, int frames) {
  Motion out(m.skeleton, m.fps, 0);
  for (int f = 0; f < std::min(frames, m.frame_count()); ++f) out.push_back(m.frame(f));
  return out;
}

void expect_round_trip(const Motion& m, const std::string& path) {
  io::write_glb(path, m);
  const Motion back = io::read_glb(path, m.fps);
  ASSERT_EQ(back.joint_count(), m.joint_count());
  ASSERT_EQ(back.frame_count(), m.frame_count());
  for (int j = 0; j < m.joint_count(); ++j) {
    const auto ju = static_cast<std::size_t>(j);
    EXPECT_EQ(back.skeleton.names[ju], m.skeleton.names[ju]);
    EXPECT_EQ(back.skeleton.parents[ju], m.skeleton.parents[ju]);
    EXPECT_EQ(back.skeleton.has_end_site[ju], m.skeleton.has_end_site[ju]);
    EXPECT_LT((back.skeleton.end_sites[ju] - m.skeleton.end_sites[ju]).norm(), 1e-6);
  }
  const auto a = joint_positions(m);
  const auto b = joint_positions(back);
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, (a[i] - b[i]).norm());
  EXPECT_LT(worst, 1e-4) << "worst joint position error (m)";
}
}  // namespace

TEST(Gltf, CmuWalkRoundTripsWithin0p1mm) {
  const Motion m = first_frames(testdata::load_sample("cmu/bvh/walking/07_01.bvh"), 240);
  const auto path = gltf_temp("legwork_walk.glb");
  expect_round_trip(m, path);
  const std::string bytes = io::read_binary_file(path);
  ASSERT_GE(bytes.size(), 12u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");  // binary container magic
  std::filesystem::remove(path);
}

TEST(Gltf, DazSkeletonRoundTrips) {
  const Motion m = io::load_bvh(testdata::sample("cmu/bvh_daz/climbing_ladder/14_33.bvh").string());
  const auto path = gltf_temp("legwork_daz.glb");
  expect_round_trip(m, path);
  std::filesystem::remove(path);
}

TEST(Gltf, WithoutMeshStillRoundTrips) {
  const Motion m = first_frames(io::load_bvh(testdata::sample("cmu/bvh/running/09_01.bvh").string()), 30);
  const auto path = gltf_temp("legwork_nomesh.glb");
  io::GltfOptions opt;
  opt.include_mesh = false;
  io::write_glb(path, m, opt);
  const auto with_mesh = gltf_temp("legwork_mesh.glb");
  io::write_glb(with_mesh, m);
  EXPECT_LT(std::filesystem::file_size(path), std::filesystem::file_size(with_mesh));
  EXPECT_EQ(io::read_glb(path, m.fps).frame_count(), m.frame_count());
  std::filesystem::remove(path);
  std::filesystem::remove(with_mesh);
}

TEST(Gltf, ErrorsAreClear) {
  const Motion m = first_frames(io::load_bvh(testdata::sample("cmu/bvh/walking/07_01.bvh").string()), 3);
  try {
    io::write_glb("/nonexistent-dir/x.glb", m);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.glb"), std::string::npos);
  }
  Motion empty(m.skeleton, 30, 0);
  EXPECT_THROW(io::write_glb(gltf_temp("legwork_empty.glb"), empty), Error);
  EXPECT_THROW(io::read_glb(testdata::sample("cmu/bvh/walking/07_01.bvh").string()), Error);
  // A truncated GLB is an error naming the file, not a crash.
  const auto path = gltf_temp("legwork_truncated.glb");
  io::write_glb(path, m);
  const std::string bytes = io::read_binary_file(path);
  io::write_text_file(path, bytes.substr(0, bytes.size() / 2));
  try {
    io::read_glb(path);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

// ---- Crafted files: nothing in a .glb is trusted -------------------------

namespace {

// A .glb split into its JSON and BIN chunks, edited and joined again.
struct Glb {
  nlohmann::json json;
  std::string bin;

  static Glb parse(const std::string& bytes) {
    auto u32 = [&](std::size_t at) {
      std::uint32_t v;
      std::memcpy(&v, bytes.data() + at, 4);
      return v;
    };
    Glb g;
    const std::uint32_t json_len = u32(12);
    g.json = nlohmann::json::parse(bytes.substr(20, json_len));
    const std::size_t bin_at = 20 + json_len;
    g.bin = bytes.substr(bin_at + 8, u32(bin_at));
    return g;
  }
  std::string bytes() const {
    std::string js = json.dump();
    while (js.size() % 4) js += ' ';
    std::string out;
    auto put = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    out += "glTF";
    put(2);
    put(static_cast<std::uint32_t>(12 + 8 + js.size() + 8 + bin.size()));
    put(static_cast<std::uint32_t>(js.size()));
    out += "JSON";
    out += js;
    put(static_cast<std::uint32_t>(bin.size()));
    out += std::string("BIN\0", 4);
    out += bin;
    return out;
  }
  // The accessor of animation 0's first sampler input (key times).
  nlohmann::json& time_accessor() { return json["accessors"][json["animations"][0]["samplers"][0]["input"].get<int>()]; }
  std::size_t time_offset() {
    const auto& acc = time_accessor();
    const auto& view = json["bufferViews"][acc["bufferView"].get<int>()];
    return view.value("byteOffset", std::size_t{0}) + acc.value("byteOffset", std::size_t{0});
  }
};

Glb sample_glb() {
  static const std::string bytes = [] {
    const std::string path = gltf_temp("legwork_crafted_base.glb");
    io::write_glb(path, first_frames(testdata::load_sample("cmu/bvh/walking/07_01.bvh"), 20));
    std::string b = io::read_binary_file(path);
    std::filesystem::remove(path);
    return b;
  }();
  return Glb::parse(bytes);
}

std::string parse_error(const std::string& bytes) {
  try {
    io::parse_glb(bytes, "crafted.glb", 30);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(Gltf, UneditedCraftBaseParses) {
  // The helper itself must round-trip, or the failures below prove nothing.
  const Motion m = io::parse_glb(sample_glb().bytes(), "crafted.glb", 30);
  EXPECT_EQ(m.joint_count(), testdata::sample_skeleton().joint_count());
  EXPECT_GT(m.frame_count(), 1);
}

TEST(Gltf, AccessorCountThatWrapsTheBoundsCheckIsRejected) {
  // 2^62 + 1 floats: count * 4 wraps to 4 bytes in 64-bit arithmetic (a heap
  // write overflow before the fix).
  Glb g = sample_glb();
  g.time_accessor()["count"] = (std::uint64_t{1} << 62) + 1;
  const std::string msg = parse_error(g.bytes());
  EXPECT_NE(msg.find("crafted.glb: animation input (4611686018427387905 elements) reaches past the end of its buffer"),
            std::string::npos)
      << msg;
}

TEST(Gltf, AccessorPastItsViewIsRejected) {
  Glb g = sample_glb();
  g.time_accessor()["byteOffset"] = std::uint64_t{1} << 40;
  EXPECT_NE(parse_error(g.bytes()).find("reaches past the end of its buffer"), std::string::npos);
}

TEST(Gltf, KeyTimesMustBeFiniteAndIncreasing) {
  Glb g = sample_glb();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(g.bin.data() + g.time_offset(), &nan, 4);
  EXPECT_NE(parse_error(g.bytes()).find("animation key time 0 of 'Hips' is not a finite time >= 0"), std::string::npos)
      << parse_error(g.bytes());
  Glb h = sample_glb();
  const float later = 1.0f;  // key 0 after key 1
  std::memcpy(h.bin.data() + h.time_offset(), &later, 4);
  EXPECT_NE(parse_error(h.bytes()).find("are not strictly increasing (key 1)"), std::string::npos)
      << parse_error(h.bytes());
}

TEST(Gltf, HugeDurationIsBoundedBeforeAllocating) {
  // The last key at 3e38 s: the sample count must be refused, not overflow an int.
  Glb g = sample_glb();
  const int count = g.time_accessor()["count"].get<int>();
  const float far = 3e38f;
  std::memcpy(g.bin.data() + g.time_offset() + 4 * static_cast<std::size_t>(count - 1), &far, 4);
  const std::string msg = parse_error(g.bytes());
  EXPECT_NE(msg.find("that is more than legwork reads (16777216 joint poses)"), std::string::npos) << msg;
}

TEST(Gltf, ExternalBufferFilesAreRefused) {
  // A crafted buffer URI must not make the reader open files on this machine.
  Glb g = sample_glb();
  g.json["buffers"].push_back({{"uri", "/etc/hostname"}, {"byteLength", 4}});
  g.json["bufferViews"].push_back({{"buffer", 1}, {"byteLength", 4}});
  const std::string msg = parse_error(g.bytes());
  EXPECT_EQ(msg, "crafted.glb: cannot read glTF binary: File not found : /etc/hostname");
}

TEST(Gltf, SampleTimeJustBelowTheLastKeyStaysInTheKeys) {
  // A time that rounds up to the last key as a float used to make
  // upper_bound return end() and read past the key vector (seen by ASan).
  const Motion m = first_frames(testdata::load_sample("cmu/bvh/walking/07_01.bvh"), 31);
  const std::string path = gltf_temp("legwork_locate_edge.glb");
  io::write_glb(path, m);
  const double last = static_cast<float>((m.frame_count() - 1) / m.fps);
  const int samples = m.frame_count() - 1;
  const double fps = samples / (last * (1 - std::ldexp(1.0, -30)));  // last sample at last * (1 - 2^-30)
  const Motion back = io::read_glb(path, fps);
  std::filesystem::remove(path);
  ASSERT_EQ(back.frame_count(), samples + 1);
  const auto a = joint_positions(m.skeleton, m.frame(m.frame_count() - 1));
  const auto b = joint_positions(back.skeleton, back.frame(back.frame_count() - 1));
  for (std::size_t j = 0; j < a.size(); ++j) EXPECT_LT((a[j] - b[j]).norm(), 1e-4) << "joint " << j;
}
