// BVH writer: Euler decomposition, the written text (layout, units, frame
// time), round trips through the reader on real CMU files, and refusals of
// motions or layouts it cannot write.
#include <legwork/io/bvh.hpp>
#include <legwork/io/text.hpp>

#include "bvh_fixture.hpp"
#include "testdata.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>
#include <unistd.h>

using namespace legwork;
using legwork::testdata::expect_same_motion;
using legwork::testdata::metres;

namespace {

using legwork::testdata::kTinyBvh;

std::string error_of(const Motion& m, const io::BvhWriteOptions& w = {}) {
  try {
    io::format_bvh(m, w);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// The lines of `text` that start (after indentation) with `word`.
std::vector<std::string> lines_starting(const std::string& text, const std::string& word) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    line.erase(0, line.find_first_not_of('\t'));
    if (line.rfind(word, 0) == 0) out.push_back(line);
  }
  return out;
}

}  // namespace

TEST(BvhWriter, QuatToEulerRecoversKnownAnglesInFileOrder) {
  // Independent oracle: R = Rz(30) Ry(-20) Rx(45) built from Eigen angle-axes.
  const Quat q = Quat(Eigen::AngleAxisd(deg2rad(30), Vec3::UnitZ())) * Quat(Eigen::AngleAxisd(deg2rad(-20), Vec3::UnitY())) *
                 Quat(Eigen::AngleAxisd(deg2rad(45), Vec3::UnitX()));
  const io::Channel zyx[3] = {io::Channel::Zrotation, io::Channel::Yrotation, io::Channel::Xrotation};
  double deg[3];
  io::quat_to_euler(q, zyx, deg);
  EXPECT_NEAR(deg[0], 30, 1e-9);
  EXPECT_NEAR(deg[1], -20, 1e-9);
  EXPECT_NEAR(deg[2], 45, 1e-9);
  // A single-axis rotation puts all of its angle on that axis in any order.
  const io::Channel xzy[3] = {io::Channel::Xrotation, io::Channel::Zrotation, io::Channel::Yrotation};
  io::quat_to_euler(Quat(Eigen::AngleAxisd(deg2rad(70), Vec3::UnitY())), xzy, deg);
  EXPECT_NEAR(deg[0], 0, 1e-9);
  EXPECT_NEAR(deg[1], 0, 1e-9);
  EXPECT_NEAR(deg[2], 70, 1e-9);
}

TEST(BvhWriter, DefaultLayoutFrameTimeAndScale) {
  auto m = io::parse_bvh(kTinyBvh, "base.bvh", metres()).motion;
  m.fps = 120;
  io::BvhWriteOptions w;
  w.scale = 100;  // metres -> centimetres
  const std::string text = io::format_bvh(m, w);
  EXPECT_EQ(lines_starting(text, "CHANNELS"),
            (std::vector<std::string>{"CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation",
                                      "CHANNELS 3 Zrotation Yrotation Xrotation"}));
  // Offsets scaled: Spine and its End Site are 0.5 m up = 50 units.
  EXPECT_EQ(lines_starting(text, "OFFSET"),
            (std::vector<std::string>{"OFFSET 0.000000 0.000000 0.000000", "OFFSET 0.000000 50.000000 0.000000",
                                      "OFFSET 0.000000 50.000000 0.000000"}));
  EXPECT_EQ(lines_starting(text, "Frames:"), std::vector<std::string>{"Frames: 2"});
  const auto ft = lines_starting(text, "Frame Time:");
  ASSERT_EQ(ft.size(), 1u);
  EXPECT_NEAR(std::stod(ft[0].substr(11)), 1.0 / 120, 1e-12);
  // Reading it back in centimetres gives the motion in metres.
  io::BvhReadOptions cm;
  cm.scale = 0.01;
  expect_same_motion(m, io::parse_bvh(text, "cm.bvh", cm).motion, 1e-6);
  // No negative zeros: an exactly zero value is written "0.000000".
  EXPECT_EQ(text.find("-0.000000"), std::string::npos);
}

TEST(BvhWriter, WriteBvhStoresTheFormattedText) {
  const auto f = io::read_bvh(testdata::sample("cmu/bvh/walking/07_01.bvh").string());
  const auto path = (std::filesystem::temp_directory_path() / ("legwork_bvh_writer_test_" + std::to_string(::getpid()) + ".bvh")).string();
  io::write_bvh(path, f.motion);
  EXPECT_EQ(io::read_text_file(path), io::format_bvh(f.motion));
  expect_same_motion(f.motion, io::read_bvh(path, metres()).motion, 1e-6);
  std::filesystem::remove(path);
}

// write_bvh streams the text in pieces of about 1 MB (a long walk is never
// held whole as text): a motion of several pieces is written byte for byte
// as format_bvh makes it, and nothing is written for a refused motion.
TEST(BvhWriter, StreamedFileOfManyPiecesEqualsTheFormattedText) {
  const auto f = io::read_bvh(testdata::sample("cmu/bvh/walking/07_01.bvh").string());
  Motion m(f.motion.skeleton, f.motion.fps, 8 * f.motion.frame_count());
  for (int i = 0; i < m.frame_count(); ++i) m.set_frame(i, f.motion.frame(i % f.motion.frame_count()));
  const std::string text = io::format_bvh(m);
  ASSERT_GT(text.size(), std::size_t{2} << 20);  // three pieces of 1 MB or more
  const auto path = (std::filesystem::temp_directory_path() / ("legwork_bvh_stream_test_" + std::to_string(::getpid()) + ".bvh")).string();
  io::write_bvh(path, m);
  EXPECT_TRUE(io::read_text_file(path) == text);
  std::filesystem::remove(path);
  m.frame(m.frame_count() - 1).rotations[3] = Quat(std::numeric_limits<double>::quiet_NaN(), 0, 0, 0);
  try {
    io::write_bvh(path, m);
    ADD_FAILURE() << "a NaN rotation was written";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "write_bvh: the motion has a non-finite joint rotation");
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST(BvhWriter, RefusalsNameTheProblem) {
  const auto f = io::parse_bvh(kTinyBvh, "base.bvh", metres());
  Motion m = f.motion;
  m.fps = 0;
  EXPECT_EQ(error_of(m), "write_bvh: frame rate must be positive, got 0.000000");
  io::BvhWriteOptions w;
  w.channels = {f.channels[0]};
  EXPECT_EQ(error_of(f.motion, w), "write_bvh: channel layout has 1 joints, skeleton has 2");
  w.channels = f.channels;
  w.channels[1].channels = {io::Channel::Zrotation, io::Channel::Xrotation};
  EXPECT_EQ(error_of(f.motion, w), "write_bvh: joint 'Spine' has a layout with 2 rotation channels; legwork writes 0 or 3");
  w.channels[1].channels = {io::Channel::Xposition, io::Channel::Zrotation, io::Channel::Yrotation, io::Channel::Xrotation};
  EXPECT_EQ(error_of(f.motion, w), "write_bvh: joint 'Spine' has a layout with 1 position channels; legwork writes 0 or 3");
  w.channels[1].channels = {};
  EXPECT_EQ(error_of(f.motion, w), "write_bvh: joint 'Spine' rotates but its layout has no rotation channels");
  m = f.motion;
  m.frame(0).rotations[1] = Quat(std::numeric_limits<double>::infinity(), 0, 0, 0);
  EXPECT_EQ(error_of(m), "write_bvh: the motion has a non-finite joint rotation");
}

TEST(BvhWriter, EulerRoundTripsInEveryOrder) {
  // quat_to_euler inverts euler_to_quat for all six Tait-Bryan orders, including near gimbal lock.
  std::array<io::Channel, 3> order = {io::Channel::Xrotation, io::Channel::Yrotation, io::Channel::Zrotation};
  std::srand(7);
  do {
    for (int i = 0; i < 200; ++i) {
      Quat q = Quat::UnitRandom();
      if (i == 0) q = io::euler_to_quat(order.data(), std::array<double, 3>{30, 90, -20}.data(), 3);
      double deg[3];
      io::quat_to_euler(q, order.data(), deg);
      const Quat back = io::euler_to_quat(order.data(), deg, 3);
      EXPECT_NEAR(std::abs(back.dot(q)), 1.0, 1e-9);
    }
  } while (std::next_permutation(order.begin(), order.end()));
}

TEST(BvhWriter, RoundTripOnRealFilesWithinOneMicro) {
  for (const char* rel : {"cmu/bvh/walking/07_01.bvh", "cmu/bvh/boxing/13_18.bvh", "cmu/bvh/swimming/79_02.bvh",
                          "cmu/bvh_daz/climbing_ladder/14_33.bvh"}) {
    SCOPED_TRACE(rel);
    const auto file = io::read_bvh(testdata::sample(rel).string());
    // In the file's own channel layout (DAZ: Z X Y), in metres.
    io::BvhWriteOptions same;
    same.channels = file.channels;
    expect_same_motion(file.motion, io::parse_bvh(io::format_bvh(file.motion, same), "rt.bvh", metres()).motion, 1e-6);
    // Default layout (Z Y X everywhere), written back in the file's units.
    io::BvhWriteOptions units;
    units.scale = 1.0 / file.report.scale;
    const auto back = io::parse_bvh(io::format_bvh(file.motion, units), "rt_units.bvh");
    EXPECT_NEAR(back.report.scale, file.report.scale, 1e-12);
    expect_same_motion(file.motion, back.motion, 1e-6);
  }
}

TEST(BvhWriter, WriterRejectsNonFiniteMotion) {
  auto m = io::parse_bvh(kTinyBvh, "base.bvh", metres()).motion;
  m.frame(1).translations[0].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_of(m), "write_bvh: the motion has a non-finite joint translation");
}

TEST(BvhWriter, WriterRefusesALayoutThatWouldLoseData) {
  auto f = io::parse_bvh(kTinyBvh, "base.bvh", metres());
  f.motion.frame(1).translations[1] += Vec3(0, 0.1, 0);  // Spine translates, its layout has rotations only
  io::BvhWriteOptions w;
  w.channels = f.channels;
  try {
    io::format_bvh(f.motion, w);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'Spine' moves away from its rest offset"), std::string::npos) << e.what();
  }
  // The default layout adds position channels and keeps the translation.
  const auto back = io::parse_bvh(io::format_bvh(f.motion), "back.bvh", metres());
  expect_same_motion(f.motion, back.motion, 1e-6);
}
