// Engine frame conversions and humanoid bone names (core/engine.hpp).
#include <legwork/core/engine.hpp>
#include <legwork/core/fk.hpp>

#include <gtest/gtest.h>

#include <cmu_sample.hpp>

#include <random>

namespace legwork {
namespace {

constexpr Engine kEngines[] = {Engine::Unity, Engine::Unreal, Engine::Godot};

TEST(Engine, ConversionsRoundTripAndComposeWithRotations) {
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  for (Engine e : kEngines)
    for (int i = 0; i < 200; ++i) {
      const Vec3 p(n(rng), n(rng), n(rng));
      const Quat q = Quat(n(rng), n(rng), n(rng), n(rng)).normalized();
      EXPECT_LT((from_engine(e, to_engine(e, p)) - p).norm(), 1e-12);
      EXPECT_LT(from_engine(e, to_engine(e, q)).angularDistance(q), 1e-12);
      // A rotated point converts like the rotation applied to the converted point.
      const double unit = e == Engine::Unreal ? 100.0 : 1.0;
      EXPECT_LT((to_engine(e, q) * to_engine(e, p) - to_engine(e, Vec3(q * p))).norm(), 1e-9 * unit) << engine_name(e);
    }
}

TEST(Engine, AxesMapAsEachEngineDefinesThem) {
  const Vec3 up = Vec3::UnitY(), forward = Vec3::UnitZ(), left = Vec3::UnitX();
  // Unity: y up, z forward, x right.
  EXPECT_EQ(to_engine(Engine::Unity, up), Vec3(0, 1, 0));
  EXPECT_EQ(to_engine(Engine::Unity, forward), Vec3(0, 0, 1));
  EXPECT_EQ(to_engine(Engine::Unity, left), Vec3(-1, 0, 0));
  // Unreal: z up, x forward, y right, centimetres.
  EXPECT_EQ(to_engine(Engine::Unreal, up), Vec3(0, 0, 100));
  EXPECT_EQ(to_engine(Engine::Unreal, forward), Vec3(100, 0, 0));
  EXPECT_EQ(to_engine(Engine::Unreal, left), Vec3(0, -100, 0));
  // Godot: y up, -z forward, x right.
  EXPECT_EQ(to_engine(Engine::Godot, forward), Vec3(0, 0, -1));
  EXPECT_EQ(to_engine(Engine::Godot, left), Vec3(-1, 0, 0));
}

TEST(Engine, RealPoseKeepsBoneLengthsInEveryEngine) {
  const Motion m = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  std::vector<Transform> g(static_cast<std::size_t>(m.joint_count()));
  forward_kinematics(m.skeleton, m.frame(30), g);
  for (Engine e : kEngines) {
    const double unit = e == Engine::Unreal ? 100.0 : 1.0;
    for (int j = 1; j < m.joint_count(); ++j) {
      const int p = m.skeleton.parents[static_cast<std::size_t>(j)];
      const double len = (g[static_cast<std::size_t>(j)].translation - g[static_cast<std::size_t>(p)].translation).norm();
      const double conv = (to_engine(e, g[static_cast<std::size_t>(j)].translation) - to_engine(e, g[static_cast<std::size_t>(p)].translation)).norm();
      EXPECT_NEAR(conv, unit * len, 1e-9 * unit);
    }
  }
}

TEST(Engine, HumanoidNamesCoverEveryRole) {
  EXPECT_EQ(humanoid_bone(Role::Pelvis), "Hips");
  EXPECT_EQ(humanoid_bone(Role::LeftShoulder), "LeftUpperArm");
  EXPECT_EQ(humanoid_bone(Role::LeftClavicle), "LeftShoulder");
  EXPECT_EQ(humanoid_bone(Role::RightToe, Humanoid::Vrm), "rightToes");
  for (int r = 0; r < kRoleCount; ++r) EXPECT_FALSE(humanoid_bone(static_cast<Role>(r)).empty());
  Engine e{};
  EXPECT_TRUE(parse_engine("unreal", e));
  EXPECT_EQ(e, Engine::Unreal);
  EXPECT_FALSE(parse_engine("blender", e));
}

}  // namespace
}  // namespace legwork
