// Tracker CSV: the documented format, dropped samples, precise errors.
#include <legwork/io/tracker_csv.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

using namespace legwork;

namespace {
const std::string kGood =
    "time,head_x,head_y,head_z,head_qw,head_qx,head_qy,head_qz,lhand_x,lhand_y,lhand_z\n"
    "0.0,0,1.7,0,1,0,0,0,0.3,1.0,0.1\n"
    "0.1,0.01,1.69,0.02,0.7071068,0,0.7071068,0,,,\n"
    "0.2,0.02,1.68,0.04,2,0,0,0,nan,1.0,0.1\r\n"
    "0.3,0.03,1.67,0.06,1,0,0,0,0.31,1.01,0.12\n";

std::string expect_error(const std::string& text) {
  try {
    io::parse_tracker_csv(text, "t.csv");
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an error for:\n" << text;
  return "";
}
}  // namespace

TEST(TrackerCsv, ParsesPointsRotationsAndDroppedSamples) {
  const auto t = io::parse_tracker_csv(kGood, "good.csv");
  ASSERT_EQ(t.sample_count(), 4);
  ASSERT_EQ(t.points.size(), 2u);
  EXPECT_DOUBLE_EQ(t.time[3], 0.3);
  const auto& head = t.point("head");
  EXPECT_TRUE(head.has_rotation);
  EXPECT_TRUE(head.position[1].isApprox(Vec3(0.01, 1.69, 0.02)));
  EXPECT_NEAR(head.rotation[1].norm(), 1.0, 1e-12);
  EXPECT_NEAR(head.rotation[2].w(), 1.0, 1e-12);  // (2,0,0,0) is normalised
  const auto& hand = t.point("lhand");
  EXPECT_FALSE(hand.has_rotation);
  EXPECT_EQ(std::vector<unsigned char>(hand.valid.begin(), hand.valid.end()), (std::vector<unsigned char>{1, 0, 0, 1}));
  EXPECT_TRUE(std::isnan(hand.position[1].x()));
  EXPECT_TRUE(std::isnan(hand.position[2].y()));  // a partly dropped sample is dropped whole
  EXPECT_TRUE(t.has("head"));
  EXPECT_FALSE(t.has("rhand"));
  try {
    (void)t.point("rhand");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("has no point 'rhand' (it has: head, lhand)"), std::string::npos) << e.what();
  }
}

TEST(TrackerCsv, FormatParseRoundTrip) {
  const auto t = io::parse_tracker_csv(kGood, "good.csv");
  const auto path = (std::filesystem::temp_directory_path() / "legwork_tracker_rt.csv").string();
  io::write_tracker_csv(path, t);
  const auto back = io::read_tracker_csv(path);
  ASSERT_EQ(back.sample_count(), t.sample_count());
  ASSERT_EQ(back.points.size(), t.points.size());
  for (std::size_t p = 0; p < t.points.size(); ++p) {
    EXPECT_EQ(back.points[p].name, t.points[p].name);
    EXPECT_EQ(back.points[p].valid, t.points[p].valid);
    for (int i = 0; i < t.sample_count(); ++i) {
      const auto iu = static_cast<std::size_t>(i);
      EXPECT_EQ(back.time[iu], t.time[iu]);  // shortest round-trip formatting is exact
      if (!t.points[p].valid[iu]) continue;
      EXPECT_EQ(back.points[p].position[iu], t.points[p].position[iu]);
      if (t.points[p].has_rotation) {
        EXPECT_EQ(back.points[p].rotation[iu].coeffs(), t.points[p].rotation[iu].coeffs());
      }
    }
  }
  std::filesystem::remove(path);
}

TEST(TrackerCsv, ErrorsNameFileLineAndColumn) {
  struct Case {
    std::string text, expect;
  };
  const std::vector<Case> cases = {
      {"", "t.csv:1:1: empty file"},
      {"\n\n", "t.csv:1:1: empty file"},
      {"t,a_x,a_y,a_z\n0,1,2,3\n", "t.csv:1:1: missing 'time' column"},
      {"a_x,time,a_y,a_z\n", "t.csv:1:1: the first column must be 'time'"},
      {"time,a_x,a_y\n0,1,2\n", "t.csv:1:6: incomplete xyz triple: point 'a' has no 'a_z' column"},
      {"time,a_x,a_y,a_z,a_qw,a_qx\n", "t.csv:1:6: incomplete orientation: point 'a' needs all of _qw, _qx, _qy, _qz"},
      {"time,a_x,a_y,a_z,speed\n", "t.csv:1:18: column 'speed' is not"},
      {"time,a_x,a_y,a_z,a_x\n", "t.csv:1:18: column 'a_x' appears twice"},
      {"time,a_x,a_y,a_z\n0,1,2,3\n0.1,1,abc,3\n", "t.csv:3:7: cell 'abc' in column 3 is not a number"},
      {"time,a_x,a_y,a_z\n0,1,2,3\n0.1, 1 , inf ,3\n", "t.csv:3:10: cell 'inf' in column 3 is not a number"},
      {"time,a_x,a_y,a_z\n0,1,2,3\n0,1,2,3\n", "t.csv:3:1: time 0 is not after the previous row's time"},
      {"time,a_x,a_y,a_z\n0.5,1,2,3\n0.25,1,2,3\n", "t.csv:3:1: time 0.25 is not after"},
      {"time,a_x,a_y,a_z\n0,1,2,3\n0.1,1,2\n", "t.csv:3:8: wrong cell count: the row has 3 cells, the header has 4"},
      {"time,a_x,a_y,a_z\n0,1,2,3,4\n", "t.csv:2:9: wrong cell count: the row has 5 cells, the header has 4"},
      {"time,a_x,a_y,a_z\n,1,2,3\n", "t.csv:2:1: the time cell is empty or NaN"},
      {"time,a_x,a_y,a_z,a_qw,a_qx,a_qy,a_qz\n0,1,2,3,0,0,0,0\n", "t.csv:2:9: orientation of 'a' is a zero quaternion"},
  };
  for (const auto& c : cases) {
    const std::string msg = expect_error(c.text);
    EXPECT_EQ(msg.rfind(c.expect, 0), 0u) << "got:      " << msg << "\nexpected: " << c.expect;
  }
}

TEST(TrackerCsv, FormatRejectsInconsistentTables) {
  io::TrackerTable t;
  t.time = {0.0, 0.1};
  t.points.push_back({"a", false, {Vec3::Zero()}, {}, {1}});
  EXPECT_THROW(io::format_tracker_csv(t), Error);
  t.points[0].position.push_back(Vec3::Ones());
  t.points[0].valid.push_back(1);
  EXPECT_NO_THROW(io::format_tracker_csv(t));
  t.time = {0.1, 0.1};
  EXPECT_THROW(io::format_tracker_csv(t), Error);
}

TEST(TrackerCsv, EncodingsAreNamedAndBinaryIsNotEchoed) {
  const std::string csv = "time,head_x,head_y,head_z\n0,0,1.7,0\n0.1,0,1.7,0\n";
  // A UTF-8 byte-order mark (Excel's "CSV UTF-8") is read as if absent.
  EXPECT_EQ(io::parse_tracker_csv("\xEF\xBB\xBF" + csv, "bom.csv").sample_count(), 2);
  // UTF-16 ("Unicode text") is named instead of "the first column must be 'time', found '??t?i?m?e'".
  std::string utf16 = "\xFF\xFE";
  for (char c : csv) utf16 += c, utf16 += '\0';
  try {
    io::parse_tracker_csv(utf16, "u16.csv");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "u16.csv: UTF-16 text; save it as UTF-8");
  }
  // Control and non-ASCII bytes of a bad cell are not copied into the message.
  try {
    io::parse_tracker_csv("time,head_x,head_y,head_z\n0,\x1b[2J\xff,1.7,0\n", "bin.csv");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("bin.csv:2:3: cell '?[2J?'"), std::string::npos) << msg;
    for (char c : msg) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << "byte " << static_cast<int>(static_cast<unsigned char>(c));
  }
}
