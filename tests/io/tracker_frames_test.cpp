// Tracker tables <-> TrackerFrames: a real walk's devices survive the round
// trip, point-name aliases, dropped samples, and errors that name the device,
// the accepted names and the points present.
#include <legwork/io/tracker_csv.hpp>

#include <legwork/core/motion.hpp>
#include <legwork/core/tracker.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cmu_sample.hpp"
#include "error_message.hpp"

using namespace legwork;

using legwork::testdata::message_of;

namespace {

// A two-sample table with one point per name; `rot` names get rotation columns.
io::TrackerTable table_with(std::initializer_list<const char*> names, std::initializer_list<const char*> rot = {}) {
  io::TrackerTable t;
  t.time = {0.0, 0.1};
  double k = 1;
  for (const char* n : names) {
    io::TrackedPoint p;
    p.name = n;
    p.position = {Vec3(k, 2 * k, 3 * k), Vec3(k + 0.5, 2 * k, 3 * k)};
    p.valid = {1, 1};
    for (const char* r : rot)
      if (std::string(r) == n) {
        p.has_rotation = true;
        p.rotation = {Quat::Identity(), Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY()))};
      }
    t.points.push_back(std::move(p));
    k += 1;
  }
  return t;
}

}  // namespace

TEST(TrackerFrames, RealWalkRoundTripsThroughATable) {
  const Motion m = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  const auto frames = tracker_frames_from_motion(m);
  ASSERT_EQ(frames.size(), static_cast<std::size_t>(m.frame_count()));
  const io::TrackerTable t = io::table_from_frames(frames);
  ASSERT_EQ(t.points.size(), 5u);  // every device of the CMU skeleton is tracked
  for (int d = 0; d < kDeviceCount; ++d) EXPECT_EQ(t.points[static_cast<std::size_t>(d)].name, device_name(static_cast<Device>(d)));
  EXPECT_TRUE(t.points[0].has_rotation);
  EXPECT_FALSE(t.points[1].has_rotation);
  const auto back = io::frames_from_table(t, "walk.csv", {Device::Head, Device::LeftFoot, Device::RightFoot});
  ASSERT_EQ(back.size(), frames.size());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    EXPECT_EQ(back[f].time, frames[f].time);
    for (int d = 0; d < kDeviceCount; ++d) {
      const auto dev = static_cast<Device>(d);
      EXPECT_TRUE(back[f][dev].valid);
      EXPECT_EQ(back[f][dev].position, frames[f][dev].position);
      // Only the head carries its rotation through the table; the others come back as identity.
      const Quat want = dev == Device::Head ? frames[f][dev].rotation : Quat::Identity();
      EXPECT_EQ(back[f][dev].rotation.coeffs(), want.coeffs());
    }
  }
}

TEST(TrackerFrames, AliasesFirstMatchAndAbsentDevices) {
  const auto t = table_with({"hmd", "LeftAnkle", "right_ankle", "left", "right_foot"}, {"hmd"});
  const auto f = io::frames_from_table(t, "a.csv");
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[1].time, 0.1);
  EXPECT_EQ(f[1].head().position, Vec3(1.5, 2, 3));
  EXPECT_TRUE(f[1].head().rotation.isApprox(Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY()))));
  EXPECT_EQ(f[0].foot(kLeft).position, Vec3(2, 4, 6));
  // right_foot is listed before right_ankle among the accepted names: it wins.
  EXPECT_EQ(f[0].foot(kRight).position, Vec3(5, 10, 15));
  EXPECT_EQ(f[0].hand(kLeft).position, Vec3(4, 8, 12));
  EXPECT_EQ(f[0].hand(kLeft).rotation.coeffs(), Quat::Identity().coeffs());
  EXPECT_FALSE(f[0].hand(kRight).valid);  // no right-hand column
  // table_from_frames writes only the devices valid somewhere, under their canonical names.
  const auto back = io::table_from_frames(f);
  std::vector<std::string> names;
  for (const auto& p : back.points) names.push_back(p.name);
  EXPECT_EQ(names, (std::vector<std::string>{"head", "left_hand", "left_foot", "right_foot"}));
}

TEST(TrackerFrames, DroppedAndUnusableSamplesAreInvalid) {
  auto t = table_with({"head", "left_hand", "right_hand"}, {"head"});
  t.points[0].position[1].y() = 1e30;  // finite but absurd: lost tracking
  t.points[1].valid[0] = 0;            // dropped in the CSV
  t.points[2].position[0].x() = std::numeric_limits<double>::quiet_NaN();
  const auto f = io::frames_from_table(t, "d.csv");
  EXPECT_TRUE(f[0].head().valid);
  EXPECT_FALSE(f[1].head().valid);
  EXPECT_FALSE(f[0].hand(kLeft).valid);
  EXPECT_TRUE(f[1].hand(kLeft).valid);
  EXPECT_FALSE(f[0].hand(kRight).valid);
  EXPECT_TRUE(f[1].hand(kRight).valid);
  // Written back, the invalid samples are marked as dropped.
  const auto back = io::table_from_frames(f);
  ASSERT_EQ(back.points.size(), 3u);
  EXPECT_EQ(back.points[0].valid, (std::vector<unsigned char>{1, 0}));
  EXPECT_EQ(back.points[1].valid, (std::vector<unsigned char>{0, 1}));
  EXPECT_EQ(back.points[2].valid, (std::vector<unsigned char>{0, 1}));
}

TEST(TrackerFrames, MissingDevicesAreNamed) {
  const auto feet = table_with({"left_foot", "right_foot"});
  EXPECT_EQ(message_of([&] { io::frames_from_table(feet, "feet.csv", {Device::LeftFoot, Device::Head}); }),
            "feet.csv: no column for the head (accepted point names: 'head', 'hmd', 'headset'); points present: "
            "left_foot, right_foot");
  EXPECT_EQ(message_of([&] { io::frames_from_table(io::TrackerTable{}, "empty.csv", {Device::RightHand}); }),
            "empty.csv: no column for the right_hand (accepted point names: 'right_hand', 'right', 'rhand', "
            "'right_wrist'); points present: none");
  const auto head = table_with({"headset"});
  EXPECT_EQ(message_of([&] { io::frames_from_table(head, "h.csv", {Device::Head}); }),
            "h.csv: the head needs orientation columns headset_qw, headset_qx, headset_qy, headset_qz");
  // Not needed: the head without rotation is read with identity.
  EXPECT_EQ(io::frames_from_table(head, "h.csv")[0].head().rotation.coeffs(), Quat::Identity().coeffs());
}
