// Tracker input sources: CSV files, motions, synthetic stepping.
#include <legwork/io/tracker_csv.hpp>
#include <legwork/wip/offline/input.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <filesystem>

namespace legwork::wip {
namespace {

TEST(Input, CsvWithoutFeetIsRefusedNamingTheFileTheDeviceAndThePointsPresent) {
  const std::string path = std::string(LEGWORK_SOURCE_DIR) + "/tests/wip/data/no_ankles.csv";
  try {
    tracker_input_from_csv(path);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("no_ankles.csv"), std::string::npos) << msg;
    EXPECT_NE(msg.find("left_foot"), std::string::npos) << msg;
    EXPECT_NE(msg.find("left_ankle"), std::string::npos) << msg;  // an accepted name
    EXPECT_NE(msg.find("left_hand"), std::string::npos) << msg;   // a point present
  }
}

TEST(Input, SyntheticTrackRoundTripsThroughCsv) {
  SyntheticOptions o;
  o.duration = 6;
  const auto in = tracker_input_synthetic(o);
  const auto path = std::filesystem::temp_directory_path() / "legwork_wip_input_test.csv";
  io::write_tracker_csv(path.string(), io::table_from_frames(in.frames));
  const auto back = tracker_input_from_csv(path.string());
  std::filesystem::remove(path);
  ASSERT_EQ(back.frames.size(), in.frames.size());
  EXPECT_NEAR(back.rate, o.rate, 1e-6);
  EXPECT_TRUE(back.still_start);
  for (std::size_t i = 0; i < in.frames.size(); ++i)
    for (int f = 0; f < 2; ++f) {
      ASSERT_EQ(back.frames[i].foot(f).valid, in.frames[i].foot(f).valid) << i;
      if (in.frames[i].foot(f).valid) {
        ASSERT_LT((back.frames[i].foot(f).position - in.frames[i].foot(f).position).norm(), 1e-4);
      }
    }
}

TEST(Input, MotionAnklesBecomeTheFeetWithTrueSwings) {
  const Motion walk = testdata::load_sample("cmu/bvh/walking/16_15.bvh");
  const auto in = tracker_input_from_motion(walk, "16_15.bvh", 30.0);
  EXPECT_FALSE(in.still_start);
  EXPECT_EQ(in.frames.size(), static_cast<std::size_t>(std::floor(walk.duration() * 30 + 1e-9)) + 1);
  EXPECT_GE(in.truth.size(), 4u);
  for (const auto& fr : in.frames) ASSERT_TRUE(usable(fr.foot(kLeft)) && usable(fr.foot(kRight)));
  Skeleton s;
  s.add_joint("Hips", -1, Vec3::Zero());
  resolve_roles(s);
  try {
    tracker_input_from_motion(Motion(s, 30, 3), "legless.bvh", 30.0);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("legless.bvh: motion has no ankle joints"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace legwork::wip
