// Motion files by extension: reading .bvh and legwork's .glb the same way,
// converting (trim, mirror, resample, BVH channel layout kept) and the
// description `legwork info` prints, on the repo's CMU sample.
#include <legwork/io/motion_file.hpp>

#include <legwork/core/types.hpp>
#include <legwork/io/gltf.hpp>

#include "testdata.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

using namespace legwork;

namespace {

std::string walk() { return testdata::sample("cmu/bvh/walking/07_01.bvh").string(); }

std::string motion_temp(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / "legwork_motion_file_test";
  std::filesystem::create_directories(d);
  return (d / name).string();
}

std::string error_of(const auto& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(MotionFile, ReadsBvhWithTheSharedOptions) {
  const io::BvhFile all = io::read_motion(walk());
  io::MotionReadOptions o;
  o.drop_first = true;
  const io::BvhFile dropped = io::read_motion(walk(), o);
  EXPECT_EQ(dropped.motion.frame_count(), all.motion.frame_count() - 1);
  EXPECT_NEAR(all.report.scale, 0.056444, 1e-5);  // CMU inches-ish units detected
  o.scale = 0.1;
  EXPECT_NEAR(io::read_motion(walk(), o).report.scale, 0.1, 1e-12);
}

TEST(MotionFile, GlbReadBackHasRolesAndDropFirst) {
  const io::BvhFile bvh = io::read_motion(walk());
  const std::string glb = motion_temp("walk.glb");
  io::write_motion(glb, bvh.motion, "walk");
  io::MotionReadOptions o;
  const io::BvhFile back = io::read_motion(glb, o);
  EXPECT_EQ(back.report.scale_reason, "glTF is in metres");
  EXPECT_GE(back.motion.skeleton.roles[Role::LeftAnkle], 0);
  EXPECT_EQ(back.report.missing_roles.size(), 0u);
  o.drop_first = true;
  EXPECT_EQ(io::read_motion(glb, o).motion.frame_count(), back.motion.frame_count() - 1);
}

TEST(MotionFile, WriteRefusesOtherExtensionsNamingTheOption) {
  const io::BvhFile bvh = io::read_motion(walk());
  EXPECT_EQ(error_of([&] { io::write_motion(motion_temp("x.fbx"), bvh.motion, "m", "--out"); }),
            "--out '" + motion_temp("x.fbx") + "' must end in .bvh or .glb");
}

TEST(MotionFile, ConvertTrimsResamplesKeepsChannelsAndMirrors) {
  const io::BvhFile src = io::read_motion(walk());
  io::ConvertOptions c;
  c.frames = "1:120";
  c.rate = 60;
  const std::string out = motion_temp("converted.bvh");
  const Motion m = io::convert_motion(src, c, out);
  EXPECT_NEAR(m.fps, 60.0, 1e-9);
  EXPECT_NEAR(m.duration(), 119 / src.motion.fps, 1.0 / 60);
  const io::BvhFile back = io::read_motion(out);
  EXPECT_EQ(back.motion.frame_count(), m.frame_count());
  ASSERT_EQ(back.channels.size(), src.channels.size());
  for (std::size_t j = 0; j < src.channels.size(); ++j) EXPECT_EQ(back.channels[j].channels.size(), src.channels[j].channels.size());
  EXPECT_NEAR(back.report.scale, src.report.scale, 1e-9);  // the file's own units kept
  // Mirrored: frame 0 (the source's frame 1) has its root x flipped.
  c.mirror = true;
  const Motion mirrored = io::convert_motion(src, c, motion_temp("mirrored.glb"));
  EXPECT_NEAR(mirrored.frame(0).translations[0].x(), -src.motion.frame(1).translations[0].x(), 1e-6);
}

TEST(MotionFile, ConvertRefusesRatesAndSizesBeforeWork) {
  const io::BvhFile src = io::read_motion(walk());
  io::ConvertOptions c;
  c.rate = 5000;
  EXPECT_EQ(error_of([&] { io::convert_motion(src, c, motion_temp("x.bvh")); }), "--rate 5000 Hz is above the limit of 1000 Hz");
  c.rate = 0;
  c.frames = "5:2";
  EXPECT_NE(error_of([&] { io::convert_motion(src, c, motion_temp("x.bvh")); }).find("--frames '5:2' is outside the clip's frames 0:"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(motion_temp("x.bvh")));
}

TEST(MotionFile, InfoNamesRolesAndRoundsNumbers) {
  const io::BvhFile f = io::read_motion(walk());
  const nlohmann::json j = io::motion_info_json(f);
  EXPECT_EQ(j["frames"], f.motion.frame_count());
  // CMU's frame time 0.008333 s is 120.000048 Hz; a person reads 120.
  EXPECT_EQ(j["fps"].get<double>(), std::round(f.motion.fps * 1000) / 1000);
  EXPECT_NEAR(j["frame_time_s"].get<double>(), 1 / f.motion.fps, 1e-12);
  EXPECT_EQ(j["roles"]["left_ankle"], "LeftFoot");
  const std::string text = io::motion_info_text(f);
  EXPECT_NE(text.find("frames:     " + std::to_string(f.motion.frame_count()) + " at 120 Hz"), std::string::npos) << text;
  EXPECT_NE(text.find("\n  Hips\n    LHipJoint\n"), std::string::npos) << text;
}
