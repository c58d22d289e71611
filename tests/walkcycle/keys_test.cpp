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
using namespace legwork::walkcycle::testing;

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
