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
