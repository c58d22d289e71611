// GLB export: write_glb -> read_glb gives back the skeleton and the motion.
#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <filesystem>

using namespace legwork;

namespace {
std::string temp(const std::string& name) { return (std::filesystem::temp_directory_path() / name).string(); }

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
  const auto path = temp("legwork_walk.glb");
  expect_round_trip(m, path);
  const std::string bytes = io::read_text_file(path);
  ASSERT_GE(bytes.size(), 12u);
  EXPECT_EQ(bytes.substr(0, 4), "glTF");  // binary container magic
  std::filesystem::remove(path);
}

TEST(Gltf, DazSkeletonRoundTrips) {
  const Motion m = io::load_bvh(testdata::sample("cmu/bvh_daz/climbing_ladder/14_33.bvh").string());
  const auto path = temp("legwork_daz.glb");
  expect_round_trip(m, path);
  std::filesystem::remove(path);
}

TEST(Gltf, WithoutMeshStillRoundTrips) {
  const Motion m = first_frames(io::load_bvh(testdata::sample("cmu/bvh/running/09_01.bvh").string()), 30);
  const auto path = temp("legwork_nomesh.glb");
  io::GltfOptions opt;
  opt.include_mesh = false;
  io::write_glb(path, m, opt);
  const auto with_mesh = temp("legwork_mesh.glb");
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
  EXPECT_THROW(io::write_glb(temp("legwork_empty.glb"), empty), Error);
  EXPECT_THROW(io::read_glb(testdata::sample("cmu/bvh/walking/07_01.bvh").string()), Error);
  // A truncated GLB is an error naming the file, not a crash.
  const auto path = temp("legwork_truncated.glb");
  io::write_glb(path, m);
  const std::string bytes = io::read_text_file(path);
  io::write_text_file(path, bytes.substr(0, bytes.size() / 2));
  try {
    io::read_glb(path);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}
