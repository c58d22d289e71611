// Role-based retargeting (src/accent/offline/retarget.cpp): a CMU walk onto its
// own and a scaled rig, and the DAZ ladder trial onto the CMU rig.
#include <legwork/accent/offline/retarget.hpp>
#include <legwork/core/fk.hpp>

#include "accent_testing.hpp"
#include "error_message.hpp"

#include <gtest/gtest.h>

namespace legwork::accent {
namespace {

Motion cmu_walk() { return testing::sample_trial("walking/07_01").motion; }
Motion daz_ladder() { return testing::sample_trial("climbing_ladder/14_33").motion; }

Vec3 at(const std::vector<Vec3>& p, int joint) { return p[static_cast<std::size_t>(joint)]; }

// Model-space direction from role a's joint to role b's joint in one pose.
Vec3 bone(const Skeleton& s, ConstPoseRef pose, Role a, Role b) {
  const auto p = joint_positions(s, pose);
  return (at(p, s.roles[b]) - at(p, s.roles[a])).normalized();
}

TEST(Retarget, OntoItsOwnRigIsTheIdentity) {
  const Motion m = cmu_walk();
  const RoleRetarget r = make_role_retarget(m.skeleton, m.skeleton);
  EXPECT_EQ(r.paired, m.joint_count());
  EXPECT_DOUBLE_EQ(r.root_scale, 1.0);
  for (int j = 0; j < m.joint_count(); ++j) EXPECT_EQ(r.source_of[static_cast<std::size_t>(j)], j);
  const Motion out = retarget_motion(m, m.skeleton);
  ASSERT_EQ(out.frame_count(), m.frame_count());
  EXPECT_EQ(out.fps, m.fps);
  const auto a = joint_positions(m), b = joint_positions(out);
  for (std::size_t i = 0; i < a.size(); i += 5) EXPECT_LT((a[i] - b[i]).norm(), 1e-9) << "entry " << i;
}

TEST(Retarget, OntoAScaledRigScalesTheRootAndKeepsEveryBoneDirection) {
  const Motion m = cmu_walk();
  Skeleton small = m.skeleton;
  small.scale(0.8);
  const Motion out = retarget_motion(m, small);
  EXPECT_NEAR(make_role_retarget(m.skeleton, small).root_scale, 0.8, 1e-12);
  for (int f = 0; f < m.frame_count(); f += 40) {
    EXPECT_LT((out.frame(f).translations[0] - 0.8 * m.frame(f).translations[0]).norm(), 1e-9);
    const auto a = joint_positions(m.skeleton, m.frame(f)), b = joint_positions(small, out.frame(f));
    // Every joint sits at 0.8 x its place relative to the root.
    for (int j = 1; j < m.joint_count(); ++j)
      EXPECT_LT(((at(b, j) - at(b, 0)) - 0.8 * (at(a, j) - at(a, 0))).norm(), 1e-9) << "frame " << f << " joint " << j;
  }
}

TEST(Retarget, DazLimbsPointWhereTheSourceLimbsPoint) {
  const Motion src = daz_ladder();
  const Skeleton& dst = cmu_walk().skeleton;
  const RoleRetarget r = make_role_retarget(src.skeleton, dst);
  EXPECT_GT(r.root_scale, 0.5);
  EXPECT_LT(r.root_scale, 2.0);
  const Motion out = retarget_motion(src, dst);
  const std::pair<Role, Role> shins[] = {{Role::LeftKnee, Role::LeftAnkle}, {Role::RightKnee, Role::RightAnkle}};
  for (int f = 0; f < src.frame_count(); f += 50)
    for (const auto& [knee, ankle] : shins) {
      // Only where the knee's one child is the ankle in both rigs is the shin the knee's bone.
      ASSERT_EQ(src.skeleton.parents[static_cast<std::size_t>(src.skeleton.roles[ankle])], src.skeleton.roles[knee]);
      ASSERT_EQ(dst.children(dst.roles[knee]).size(), 1u);
      EXPECT_LT((bone(dst, out.frame(f), knee, ankle) - bone(src.skeleton, src.frame(f), knee, ankle)).norm(), 1e-6)
          << "frame " << f << " " << role_name(knee);
    }
}

TEST(Retarget, AtHeadPutsTheHeadWhereTheSourceHeadIs) {
  const Motion src = daz_ladder();
  const Skeleton& dst = cmu_walk().skeleton;
  const Motion out = retarget_motion_at_head(src, dst);
  for (int f = 0; f < src.frame_count(); f += 25) {
    const auto a = joint_positions(src.skeleton, src.frame(f)), b = joint_positions(dst, out.frame(f));
    EXPECT_LT((at(b, dst.roles[Role::Head]) - at(a, src.skeleton.roles[Role::Head])).norm(), 1e-9) << "frame " << f;
  }
}

TEST(Retarget, ASourceWithoutTheNeededRolesIsNamed) {
  const Skeleton cmu = cmu_walk().skeleton;
  Skeleton partial = cmu;  // a rig on which the left hand and the right ankle were not found
  partial.roles[Role::LeftHand] = -1;
  partial.roles[Role::RightAnkle] = -1;
  const std::string expected = "cannot retarget: the source skeleton has no joint for role(s) " +
                               std::string(role_name(Role::LeftHand)) + ", " + std::string(role_name(Role::RightAnkle));
  EXPECT_EQ(testdata::message_of([&] { (void)make_role_retarget(partial, cmu); }), expected);
  // The other way round nothing is missing: a destination without a role needs no source for it.
  EXPECT_EQ(testdata::message_of([&] { (void)make_role_retarget(cmu, partial); }), "(no error)");
  // Optional roles (toes) may be missing from the source.
  Skeleton no_toes = cmu;
  no_toes.roles[Role::LeftToe] = no_toes.roles[Role::RightToe] = -1;
  EXPECT_EQ(testdata::message_of([&] { (void)make_role_retarget(no_toes, cmu); }), "(no error)");
}

}  // namespace
}  // namespace legwork::accent
