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

namespace {
// The CMU body plus `pairs` left/right helper joints (a 100,000-joint rig took
// 9.6 s to resolve when name lookups were linear scans). Helpers hang in
// chains of 200 off the chest, so depths reach ~200 too.
Skeleton cmu_with_helpers(int pairs) {
  Skeleton s = io::load_bvh(testdata::sample("cmu/bvh/walking/07_01.bvh").string()).skeleton;
  const int chest = s.require("Spine1");
  for (const char* side : {"Left", "Right"}) {
    int parent = chest;
    for (int i = 0; i < pairs; ++i) {
      parent = s.add_joint(std::string(side) + "Helper" + std::to_string(i), i % 200 == 0 ? chest : parent, Vec3(0, 0.01, 0));
    }
  }
  return s;
}
}  // namespace

TEST(Roles, HundredThousandJointsResolveWithMirrorPairs) {
  Skeleton s = cmu_with_helpers(50000);
  ASSERT_EQ(s.joint_count(), 31 + 100000);
  const auto missing = resolve_roles(s);
  for (Role r : missing) EXPECT_FALSE(role_is_required(r)) << role_name(r);
  EXPECT_EQ(s.names[static_cast<std::size_t>(s.roles[Role::LeftAnkle])], "LeftFoot");
  EXPECT_EQ(s.names[static_cast<std::size_t>(s.roles[Role::Head])], "Head");
  for (int i : {0, 1, 199, 200, 49999}) {
    const int l = s.find("LeftHelper" + std::to_string(i));
    const int r = s.find("RightHelper" + std::to_string(i));
    ASSERT_GE(l, 0);
    EXPECT_EQ(s.mirror[static_cast<std::size_t>(l)], r);
    EXPECT_EQ(s.mirror[static_cast<std::size_t>(r)], l);
  }
  // The body is measured the same with or without the helpers.
  const double plain = measure_body(io::load_bvh(testdata::sample("cmu/bvh/walking/07_01.bvh").string()).skeleton).standing_height;
  EXPECT_NEAR(measure_body(s).standing_height, plain, 1e-9);
}

TEST(Roles, HundredThousandJointBvhReads) {
  // Duplicate checks while reading used to scan every earlier joint.
  std::string text = "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Yrotation Xrotation\n";
  for (int i = 0; i < 100000; ++i) text += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 0.01 0\nCHANNELS 0\n}\n";
  text += "}\nMOTION\nFrames: 2\nFrame Time: 0.01\n0 0 0\n0 0 90\n";
  io::BvhReadOptions o;
  o.scale = 1;
  const auto f = io::parse_bvh(text, "wide.bvh", o);
  EXPECT_EQ(f.motion.joint_count(), 100001);
  EXPECT_EQ(f.motion.frame_count(), 2);
  // A duplicate far down the list is still found.
  const std::string dup = text.substr(0, text.find("MOTION") - 2) + "JOINT j5\n{\nOFFSET 0 0 0\nCHANNELS 0\n}\n}\n" +
                          text.substr(text.find("MOTION"));
  EXPECT_THROW(
      {
        try {
          io::parse_bvh(dup, "dup.bvh", o);
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("duplicate joint name 'j5'"), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
}
