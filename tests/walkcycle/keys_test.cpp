// Walk key-pose files (offline/keys.cpp): the shipped walks load, bad files
// give clear errors.
#include <legwork/core/fk.hpp>
#include <legwork/core/mirror.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/measure.hpp>

#include "testdata.hpp"
#include "walk_samples.hpp"

#include <cstdio>
#include <filesystem>

#include <unistd.h>

using namespace legwork;
using namespace legwork::walkcycle;
using namespace legwork::walkcycle::samples;

TEST(WalkKeys, ShippedWalksLoadWithTheirOwnSkeletonPath) {
  for (const auto& w : kWalks) {
    const std::string sk = walk_skeleton_path(walk_file(w));
    ASSERT_FALSE(sk.empty()) << w;
    EXPECT_TRUE(std::filesystem::exists(sk)) << sk;
    const auto keys = read_walk_keys(walk_file(w), cmu_skeleton());
    EXPECT_EQ(keys.name, w);
    EXPECT_GE(keys.frames_per_cycle, 24);
    EXPECT_GT(keys.keys[2].rotations.size(), 10u);
  }
}

TEST(WalkKeys, BadFilesGiveClearErrors) {
  const auto& s = cmu_skeleton();
  auto parse = [&](const std::string& text) { return expect_error([&] { parse_walk_keys(text, s, "bad.json"); }); };
  const std::string ok_keys = R"("contact": {}, "down": {}, "pass": {}, "up": {})";
  auto msg = parse(R"({"keys": {)" + ok_keys + R"(, "passing": {}}})");
  EXPECT_NE(msg.find("bad.json"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown key pose 'passing'"), std::string::npos) << msg;
  msg = parse(R"({"keys": {"contact": {}, "down": {}, "pass": {}}})");
  EXPECT_NE(msg.find("missing key pose 'up'"), std::string::npos) << msg;
  msg = parse(R"({"keys": {"contact": {"rotations": {"LeftKnee": [0, 0, 0]}}, "down": {}, "pass": {}, "up": {}}})");
  EXPECT_NE(msg.find("keys.contact.rotations.LeftKnee"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown joint"), std::string::npos) << msg;
  msg = parse(R"({"keys": {"contact": {"rotations": {"LeftLeg": [0, NaN, 0]}}, "down": {}, "pass": {}, "up": {}}})");
  EXPECT_NE(msg.find("not valid JSON"), std::string::npos) << msg;
  EXPECT_NE(msg.find("line 1"), std::string::npos) << msg;
  msg = parse(R"({"keys": {"contact": {"rotations": {"LeftLeg": [0, null, 0]}}, "down": {}, "pass": {}, "up": {}}})");
  EXPECT_NE(msg.find("keys.contact.rotations.LeftLeg[1]"), std::string::npos) << msg;
  msg = parse(R"({"keys": {"contact": {"rotations": {"LeftLeg": [0, 1e999, 0]}}, "down": {}, "pass": {}, "up": {}}})");
  EXPECT_FALSE(msg.empty());
  msg = parse(R"({"timing": {"down": 5, "pass": 4}, "keys": {)" + ok_keys + "}}");
  EXPECT_NE(msg.find("timing"), std::string::npos) << msg;
  msg = parse(R"({"frames_per_cycle": 23, "keys": {)" + ok_keys + "}}");
  EXPECT_NE(msg.find("frames_per_cycle"), std::string::npos) << msg;
  // Role names are accepted in place of joint names.
  auto k = parse_walk_keys(R"({"keys": {"contact": {"rotations": {"left_knee": [10, 0, 0]}}, "down": {}, "pass": {}, "up": {}}})", s, "ok.json");
  ASSERT_NE(k.keys[0].find(s.find("LeftLeg")), nullptr);
}

TEST(WalkKeys, CopiedWalkFindsItsSkeletonBesideIt) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("legwork_portable_walk_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string walk = (dir / "normal.json").string();
  fs::copy_file(walk_file("normal"), walk);
  // Copied alone: its "../cmu/bvh/walking/07_01.bvh" is not there; the error says where it looked and what to do.
  const std::string err = expect_error([&] { load_walk(walk); });
  EXPECT_NE(err.find("its skeleton \"../cmu/bvh/walking/07_01.bvh\" was not found"), std::string::npos) << err;
  EXPECT_NE(err.find((dir / "07_01.bvh").string()), std::string::npos) << err;
  EXPECT_NE(err.find("pass --skeleton FILE.bvh"), std::string::npos) << err;
  // --skeleton still works, and a copy of the BVH next to the walk is found.
  const std::string bvh = (testdata::source_dir() / "data/cmu/bvh/walking/07_01.bvh").string();
  EXPECT_EQ(load_walk(walk, bvh).skeleton.joint_count(), cmu_skeleton().joint_count());
  fs::copy_file(bvh, dir / "07_01.bvh");
  EXPECT_EQ(walk_skeleton_path(walk), (dir / "07_01.bvh").string());
  const WalkFile w = load_walk(walk);
  EXPECT_EQ(w.skeleton.names, cmu_skeleton().names);
  EXPECT_EQ(format_walk_keys(w.keys, w.skeleton), format_walk_keys(read_walk_keys(walk_file("normal"), cmu_skeleton()), cmu_skeleton()));
  fs::remove_all(dir);
}

// Issue 14, item 5: heel strike and toe-off in the normal walk's keys, as an
// animator poses them (Williams' contact: front heel on the floor, toes up;
// back foot on its ball, heel up; down: front foot flat; up: the stance foot
// rolls onto its ball). Pitch = angle of the heel-to-ball line above the
// floor, degrees (+ = toes up); heights in mm above the floor of the key.
TEST(WalkKeys, NormalWalkStrikesWithTheHeelAndPushesOffTheBall) {
  const CycleModel m = shipped("normal");
  std::vector<Transform> g(static_cast<std::size_t>(m.skeleton.joint_count()));
  struct Foot {
    double pitch, heel_mm, ball_mm, tip_mm;
  };
  auto foot = [&](int key, bool left) {
    forward_kinematics(m.skeleton, m.step_keys[static_cast<std::size_t>(key)], g);
    const FootPivots& f = m.foot(left);
    const Transform& a = g[static_cast<std::size_t>(f.ankle)];
    const Vec3 heel = a.apply(f.heel_local), ball = a.apply(f.ball_local);
    const Vec3 tip = end_site_position(m.skeleton, g, f.toe);
    const double run = std::hypot(ball.x() - heel.x(), ball.z() - heel.z());
    return Foot{rad2deg(std::atan2(ball.y() - heel.y(), run)), heel.y() * 1e3, ball.y() * 1e3, tip.y() * 1e3};
  };
  const char* names[] = {"contact", "down", "pass", "up"};
  for (int k = 0; k < 4; ++k)
    for (bool left : {true, false}) {
      const Foot f = foot(k, left);
      std::printf("[walkcycle] normal %-7s %s foot: pitch %+6.1f deg, heel %6.1f mm, ball %6.1f mm, toe tip %6.1f mm\n", names[k],
                  left ? "left " : "right", f.pitch, f.heel_mm, f.ball_mm, f.tip_mm);
    }
  const Foot front = foot(0, true), back = foot(0, false);
  // Contact: the front heel strikes (on the floor, the foot's lowest point), toes up.
  EXPECT_LT(std::abs(front.heel_mm), 3.0);
  EXPECT_GE(front.pitch, 12.0);
  EXPECT_LE(front.pitch, 35.0);
  EXPECT_GT(front.tip_mm, 40.0);
  // The back foot is on its ball, heel up, toes on the floor.
  EXPECT_LT(std::abs(back.ball_mm), 10.0);
  EXPECT_LE(back.pitch, -12.0);
  EXPECT_GT(back.heel_mm, 40.0);
  // Down: the front foot has come flat.
  EXPECT_LT(std::abs(foot(1, true).pitch), 6.0);
  // Up: the stance foot has rolled onto its ball (heel up).
  EXPECT_LE(foot(3, true).pitch, -10.0);
}
