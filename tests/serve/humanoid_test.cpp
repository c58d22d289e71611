// Humanoid bones for VMC output on the CMU skeleton and a real pose.
#include <legwork/core/engine.hpp>
#include <legwork/core/fk.hpp>
#include <legwork/serve/humanoid.hpp>

#include "cmu_sample.hpp"

#include <gtest/gtest.h>

namespace legwork::serve {
namespace {

TEST(Humanoid, CmuSkeletonMapsTwentyOneBonesWithFoldedParents) {
  const Skeleton& skel = testdata::sample_skeleton();
  const auto bones = humanoid_bones(skel);
  ASSERT_EQ(bones.size(), 21u);
  EXPECT_EQ(bones[0].name, "Hips");
  EXPECT_EQ(bones[0].parent, -1);
  const auto find = [&](std::string_view n) {
    for (std::size_t i = 0; i < bones.size(); ++i)
      if (bones[i].name == n) return static_cast<int>(i);
    return -1;
  };
  // LeftUpperLeg hangs on Hips although CMU has LHipJoint in between.
  EXPECT_EQ(bones[static_cast<std::size_t>(find("LeftUpperLeg"))].parent, find("Hips"));
  EXPECT_EQ(skel.names[static_cast<std::size_t>(bones[static_cast<std::size_t>(find("LeftUpperLeg"))].joint)], "LeftUpLeg");
  EXPECT_EQ(bones[static_cast<std::size_t>(find("LeftHand"))].parent, find("LeftLowerArm"));
  EXPECT_EQ(bones[static_cast<std::size_t>(find("LeftShoulder"))].parent, find("Chest"));
}

TEST(Humanoid, ChainedLocalsGiveBackTheWorldPositionsInUnitysFrame) {
  const Motion m = testdata::load_sample("cmu/bvh/walking/07_02.bvh");
  const auto bones = humanoid_bones(m.skeleton);
  std::vector<Transform> model(static_cast<std::size_t>(m.joint_count()));
  std::vector<BoneTransform> out(bones.size());
  forward_kinematics(m.skeleton, m.frame(100), model);
  humanoid_pose(bones, model, out);
  std::vector<Transform> world(bones.size());
  double worst = 0;
  for (std::size_t i = 0; i < bones.size(); ++i) {
    EXPECT_NEAR(out[i].rotation.norm(), 1.0, 1e-9);
    const Transform local{out[i].rotation, out[i].position};
    world[i] = bones[i].parent < 0 ? local : world[static_cast<std::size_t>(bones[i].parent)] * local;
    const Vec3 back = from_engine(Engine::Unity, world[i].translation);
    worst = std::max(worst, (back - model[static_cast<std::size_t>(bones[i].joint)].translation).norm());
  }
  EXPECT_LT(worst, 1e-9);
}

}  // namespace
}  // namespace legwork::serve
