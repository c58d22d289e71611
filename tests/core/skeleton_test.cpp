#include <legwork/core/measure.hpp>
#include <legwork/core/skeleton.hpp>
#include <legwork/io/bvh.hpp>

#include "testdata.hpp"

using namespace legwork;

namespace {
Skeleton names_only(std::initializer_list<std::pair<const char*, int>> joints) {
  Skeleton s;
  for (auto [n, p] : joints) s.add_joint(n, p, Vec3(0, 0.1, 0));
  return s;
}
}  // namespace

TEST(Roles, CmuSkeletonResolvesEveryRole) {
  auto m = io::load_bvh(testdata::sample("cmu/bvh/walking/07_01.bvh").string());
  const auto& s = m.skeleton;
  auto name = [&](Role r) { return s.roles[r] >= 0 ? s.names[static_cast<std::size_t>(s.roles[r])] : std::string("-"); };
  EXPECT_EQ(name(Role::Pelvis), "Hips");
  EXPECT_EQ(name(Role::LeftHip), "LeftUpLeg");
  EXPECT_EQ(name(Role::LeftKnee), "LeftLeg");
  EXPECT_EQ(name(Role::LeftAnkle), "LeftFoot");
  EXPECT_EQ(name(Role::LeftToe), "LeftToeBase");
  EXPECT_EQ(name(Role::RightHand), "RightHand");
  EXPECT_EQ(name(Role::RightElbow), "RightForeArm");
  EXPECT_EQ(name(Role::RightShoulder), "RightArm");
  EXPECT_EQ(name(Role::RightClavicle), "RightShoulder");
  EXPECT_EQ(name(Role::Head), "Head");
  EXPECT_EQ(name(Role::Neck), "Neck");
  EXPECT_EQ(name(Role::Spine), "LowerBack");
  EXPECT_EQ(name(Role::Chest), "Spine1");
  EXPECT_EQ(s.names[static_cast<std::size_t>(s.mirror[static_cast<std::size_t>(s.find("LHipJoint"))])], "RHipJoint");
  EXPECT_EQ(s.names[static_cast<std::size_t>(s.mirror[static_cast<std::size_t>(s.find("LThumb"))])], "RThumb");
  EXPECT_EQ(s.mirror[static_cast<std::size_t>(s.find("Spine"))], s.find("Spine"));
}

TEST(Roles, DazSkeletonResolves) {
  auto m = io::load_bvh(testdata::sample("cmu/bvh_daz/climbing_ladder/14_33.bvh").string());
  const auto& s = m.skeleton;
  EXPECT_EQ(s.names[static_cast<std::size_t>(s.roles[Role::LeftHip])], "lThigh");
  EXPECT_EQ(s.names[static_cast<std::size_t>(s.roles[Role::LeftKnee])], "lShin");
  EXPECT_EQ(s.names[static_cast<std::size_t>(s.roles[Role::RightHand])], "rHand");
  EXPECT_EQ(s.names[static_cast<std::size_t>(s.roles[Role::RightShoulder])], "rShldr");
  EXPECT_EQ(s.names[static_cast<std::size_t>(s.roles[Role::Pelvis])], "hip");
  EXPECT_EQ(s.names[static_cast<std::size_t>(s.roles[Role::Head])], "head");
}

TEST(Roles, MixamoAndSuffixPatterns) {
  auto mix = names_only({{"mixamorig:Hips", -1}, {"mixamorig:Spine", 0}, {"mixamorig:Neck", 1}, {"mixamorig:Head", 2},
                         {"mixamorig:HeadTop_End", 3}, {"mixamorig:LeftShoulder", 1}, {"mixamorig:LeftArm", 5},
                         {"mixamorig:LeftForeArm", 6}, {"mixamorig:LeftHand", 7}, {"mixamorig:RightShoulder", 1},
                         {"mixamorig:RightArm", 9}, {"mixamorig:RightForeArm", 10}, {"mixamorig:RightHand", 11},
                         {"mixamorig:LeftUpLeg", 0}, {"mixamorig:LeftLeg", 13}, {"mixamorig:LeftFoot", 14},
                         {"mixamorig:LeftToeBase", 15}, {"mixamorig:RightUpLeg", 0}, {"mixamorig:RightLeg", 17},
                         {"mixamorig:RightFoot", 18}, {"mixamorig:RightToeBase", 19}});
  auto missing = resolve_roles(mix);
  EXPECT_TRUE(missing.empty());
  EXPECT_EQ(mix.roles[Role::Head], 3);
  EXPECT_EQ(mix.roles[Role::LeftClavicle], 5);
  EXPECT_EQ(mix.mirror[16], 20);

  auto ue = names_only({{"pelvis", -1}, {"spine_01", 0}, {"neck_01", 1}, {"head", 2}, {"upperarm_l", 1},
                        {"lowerarm_l", 4}, {"hand_l", 5}, {"upperarm_r", 1}, {"lowerarm_r", 7}, {"hand_r", 8},
                        {"thigh_l", 0}, {"calf_l", 10}, {"foot_l", 11}, {"thigh_r", 0}, {"calf_r", 13}, {"foot_r", 14}});
  require_roles(ue, "ue-style");
  EXPECT_EQ(ue.roles[Role::RightKnee], 14);
  EXPECT_EQ(ue.mirror[4], 7);
}

TEST(Roles, MissingLegsIsAClearError) {
  auto arms_only = names_only({{"Hips", -1}, {"Spine", 0}, {"Head", 1}, {"LeftArm", 1}, {"LeftForeArm", 3},
                               {"LeftHand", 4}, {"RightArm", 1}, {"RightForeArm", 6}, {"RightHand", 7}});
  try {
    require_roles(arms_only, "arms.bvh");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("arms.bvh"), std::string::npos);
    EXPECT_NE(msg.find("left_ankle"), std::string::npos);
    EXPECT_NE(msg.find("right_knee"), std::string::npos);
  }
}

TEST(Units, CmuAndDazConvertToPlausibleHumans) {
  for (const char* rel : {"cmu/bvh/walking/07_01.bvh", "cmu/bvh/running/35_17.bvh", "cmu/bvh_daz/climbing_ladder/14_33.bvh"}) {
    auto f = io::read_bvh(testdata::sample(rel).string());
    auto b = measure_body(f.motion.skeleton);
    EXPECT_GT(b.standing_height, 1.4) << rel;
    EXPECT_LT(b.standing_height, 2.0) << rel;
    EXPECT_GT(b.leg_length, 0.6) << rel;
    EXPECT_LT(b.leg_length, 1.1) << rel;
  }
  EXPECT_NEAR(io::read_bvh(testdata::sample("cmu/bvh/walking/07_01.bvh").string()).report.scale, kCmuUnitMetres, 1e-12);
  EXPECT_NEAR(io::read_bvh(testdata::sample("cmu/bvh_daz/climbing_ladder/14_33.bvh").string()).report.scale, 0.01, 1e-12);
  EXPECT_EQ(guess_unit_scale(7000.0), 0.0);
}
