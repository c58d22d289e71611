// Malformed BVH inputs: each gives its own clear error naming the file and
// line (never a crash or a silently wrong motion).
#include <legwork/io/bvh.hpp>

#include <gtest/gtest.h>

#include "bvh_fixture.hpp"

#include <set>
#include <string>

using namespace legwork;
using legwork::testdata::metres;

namespace {

// A tiny valid file (line numbers in bvh_fixture.hpp); the cases below each
// break one thing in it.
const std::string kValid =
    legwork::testdata::kTinyBvhHeader +
    "0 1 0 0 0 0 10 20 30\n"
    "0 1 0.1 0 0 0 10 20 30\n";

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << "test setup: '" << from << "' not in the file";
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

struct Case {
  const char* name;
  std::string text;
  int line;            // expected line in "test.bvh:<line>:"
  const char* expect;  // expected part of the message
};

std::vector<Case> cases() {
  const std::string& v = kValid;
  return {
      {"empty_file", "", 1, "expected 'HIERARCHY' at the start of a BVH file, found end of file"},
      {"not_bvh", "hello world\n", 1, "expected 'HIERARCHY' at the start of a BVH file, found 'hello'"},
      {"empty_hierarchy", "HIERARCHY\nMOTION\nFrames: 1\nFrame Time: 0.1\n\n", 2, "empty hierarchy"},
      {"missing_frames", replace(v, "Frames: 2\n", ""), 17, "missing 'Frames:' line"},
      {"too_few_values", replace(v, "0 1 0.1 0 0 0 10 20 30", "0 1 0.1 0 0 0 10 20"), 20,
       "motion line has 8 values, the hierarchy declares 9 channels"},
      {"unknown_channel", replace(v, "3 Zrotation Yrotation Xrotation", "3 Zrotation Yrotation Wrotation"), 9,
       "unknown channel 'Wrotation' for joint 'Spine'"},
      {"nan_value", replace(v, "0 1 0 0 0 0 10 20 30", "0 1 0 0 nan 0 10 20 30"), 19,
       "motion line value 5 is not finite (NaN or Inf): 'nan'"},
      {"inf_value", replace(v, "0 1 0 0 0 0 10 20 30", "0 1 0 0 0 0 10 inf 30"), 19, "value 8 is not finite"},
      {"more_lines_than_declared", v + "0 1 0.2 0 0 0 10 20 30\n", 17, "'Frames: 2' but the file has 3 motion lines"},
      {"fewer_lines_than_declared", replace(v, "Frames: 2", "Frames: 3"), 17,
       "'Frames: 3' but the file has 2 motion lines"},
      {"missing_closing_brace", replace(v, "  }\n}\nMOTION", "  }\nMOTION"), 15, "missing '}' closing joint 'Hips'"},
      {"channel_count_too_big", replace(v, "3 Zrotation Yrotation Xrotation", "4 Zrotation Yrotation Xrotation"), 9,
       "CHANNELS of joint 'Spine' declares 4 channels but lists 3"},
      {"channel_count_too_small", replace(v, "3 Zrotation Yrotation Xrotation", "2 Zrotation Yrotation Xrotation"), 9,
       "CHANNELS of joint 'Spine' lists more channels than its count (extra 'Xrotation')"},
      {"channel_count_out_of_range", replace(v, "3 Zrotation Yrotation Xrotation", "7 Zrotation Yrotation Xrotation"), 9,
       "CHANNELS of joint 'Spine' needs a count from 0 to 6, found '7'"},
      {"repeated_channel", replace(v, "3 Zrotation Yrotation Xrotation", "3 Zrotation Zrotation Xrotation"), 9,
       "channel Zrotation repeated for joint 'Spine'"},
      {"duplicate_joint", replace(v, "JOINT Spine", "JOINT Hips"), 6, "duplicate joint name 'Hips'"},
      {"non_numeric_offset", replace(v, "OFFSET 0 0.5 0\n    CHANNELS", "OFFSET 0 abc 0\n    CHANNELS"), 8,
       "expected a number for OFFSET of joint 'Spine', found 'abc'"},
      {"infinite_offset", replace(v, "OFFSET 0 0.5 0\n    CHANNELS", "OFFSET 0 1e999 0\n    CHANNELS"), 8,
       "OFFSET of joint 'Spine' is not finite or out of range ('1e999')"},
      {"missing_offset", replace(v, "    OFFSET 0 0.5 0\n    CHANNELS", "    CHANNELS"), 13, "joint 'Spine' has no OFFSET"},
      {"missing_motion", replace(v, "MOTION\n", ""), 16, "expected 'MOTION' after the hierarchy, found 'Frames:'"},
      {"zero_frame_time", replace(v, "Frame Time: 0.1", "Frame Time: 0"), 18, "'Frame Time:' must be a positive"},
      {"negative_frame_time", replace(v, "Frame Time: 0.1", "Frame Time: -0.01"), 18, "'Frame Time:' must be a positive"},
      {"missing_frame_time", replace(v, "Frame Time: 0.1\n", ""), 18, "missing 'Frame Time:' line"},
      {"fractional_frames", replace(v, "Frames: 2", "Frames: 2.5"), 17, "'Frames:' needs a whole number from 0 to 100000000, found '2.5'"},
      {"truncated_in_hierarchy", v.substr(0, v.find("0.5 0\n    CHANNELS")), 8,
       "expected a number for OFFSET of joint 'Spine', found end of file"},
      {"truncated_in_motion", v.substr(0, v.size() - 10), 20, "motion line has 6 values, the hierarchy declares 9"},
      {"text_after_values", replace(v, "0 1 0 0 0 0 10 20 30", "0 1 0 0 0 0 10 20 30 foo"), 19,
       "motion line has more than the 9 values the hierarchy declares (extra 'foo')"},
      {"non_numeric_value", replace(v, "0 1 0.1 0 0 0", "0 1 0.1 0 x 0"), 20, "motion line value 5 is not a number: 'x'"},
      {"text_after_frame_time", replace(v, "Frame Time: 0.1", "Frame Time: 0.1 fps"), 18,
       "unexpected text after Frame Time value"},
      {"end_without_site", replace(v, "End Site", "End Point"), 10, "expected 'Site' after 'End', found 'Point'"},
      {"two_roots", replace(v, "}\nMOTION", "}\nROOT Other\n{\n OFFSET 0 0 0\n CHANNELS 0\n}\nMOTION"), 16,
       "more than one ROOT"},
      {"no_frames", replace(replace(v, "Frames: 2", "Frames: 0"), "0 1 0 0 0 0 10 20 30\n0 1 0.1 0 0 0 10 20 30\n", ""),
       17, "the file has no motion frames"},
      {"joint_without_name", replace(v, "JOINT Spine", "JOINT"), 7, "expected a joint name after JOINT/ROOT, found '{'"},
      // Absurd frame times: 1e300 s overflowed every derived sample count
      // (SIGSEGV in 'wip --input'), 1e4 s made a 2-frame file use 5.67 GB.
      {"frame_time_1e300", replace(v, "Frame Time: 0.1", "Frame Time: 1e300"), 18,
       "'Frame Time: 1e+300' is outside 0.0001 to 10 seconds"},
      {"frame_time_1e4", replace(v, "Frame Time: 0.1", "Frame Time: 1e4"), 18,
       "'Frame Time: 10000' is outside 0.0001 to 10 seconds"},
      {"frame_time_1e-7", replace(v, "Frame Time: 0.1", "Frame Time: 1e-7"), 18,
       "'Frame Time: 1e-07' is outside 0.0001 to 10 seconds"},
      // Lengths that overflow forward kinematics to Inf.
      {"offset_1e300", replace(v, "OFFSET 0 0.5 0\n    CHANNELS", "OFFSET 0 1e300 0\n    CHANNELS"), 8,
       "OFFSET of joint 'Spine' is beyond 1e+09 file units"},
      {"end_site_1e300", replace(v, "      OFFSET 0 0.5 0", "      OFFSET 0 1e300 0"), 12,
       "End Site OFFSET of joint 'Spine' is beyond 1e+09 file units"},
      {"position_1e300", replace(v, "0 1 0.1 0 0 0 10 20 30", "0 1e300 0.1 0 0 0 10 20 30"), 20,
       "motion line value 2 is a position beyond 1e+09 file units"},
      // Names go into JSON and glTF: a Latin-1 name must fail here, by line.
      {"joint_name_not_utf8", replace(v, "JOINT Spine", "JOINT Sp\xe9ne"), 6,
       "joint name 'Sp?ne' is not UTF-8 text"},
  };
}

}  // namespace

TEST(BvhErrors, EachMalformedInputHasItsOwnMessageWithLine) {
  const auto all = cases();
  ASSERT_GE(all.size(), 15u);
  std::set<std::string> messages;
  for (const auto& c : all) {
    SCOPED_TRACE(c.name);
    try {
      io::parse_bvh(c.text, "test.bvh", metres());
      ADD_FAILURE() << c.name << ": expected an error";
    } catch (const Error& e) {
      const std::string msg = e.what();
      const std::string prefix = "test.bvh:" + std::to_string(c.line) + ": ";
      EXPECT_EQ(msg.rfind(prefix, 0), 0u) << "message: " << msg << "\nexpected prefix: " << prefix;
      EXPECT_NE(msg.find(c.expect), std::string::npos) << "message: " << msg << "\nexpected: " << c.expect;
      messages.insert(msg);
    }
  }
  EXPECT_EQ(messages.size(), all.size()) << "two malformed inputs gave the same message";
}

TEST(BvhErrors, ValidBaseFileParses) {
  auto f = io::parse_bvh(kValid, "test.bvh", metres());
  EXPECT_EQ(f.motion.frame_count(), 2);
  EXPECT_EQ(f.motion.joint_count(), 2);
  EXPECT_DOUBLE_EQ(f.motion.fps, 10.0);
}

TEST(BvhErrors, UnknownUnitsAskForAScale) {
  // 1000 km tall: no unit fits, the reader must say so rather than guess.
  const std::string huge = replace(replace(kValid, "OFFSET 0 0.5 0\n    CHANNELS", "OFFSET 0 5e8 0\n    CHANNELS"),
                                   "      OFFSET 0 0.5 0", "      OFFSET 0 5e8 0");
  try {
    io::parse_bvh(huge, "huge.bvh");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("huge.bvh: rest height"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fits no known unit"), std::string::npos) << e.what();
  }
}

TEST(BvhErrors, DeepNestingIsAnErrorNotAStackOverflow) {
  std::string deep = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 0\n";
  for (int i = 0; i < 100000; ++i) deep += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 0 0\nCHANNELS 0\n";
  EXPECT_THROW(io::parse_bvh(deep, "deep.bvh", metres()), Error);
}

TEST(BvhErrors, HugeDeclaredFrameCountDoesNotAllocate) {
  // A bogus 'Frames:' must produce an error, not a multi-gigabyte reservation.
  const std::string bogus = replace(kValid, "Frames: 2", "Frames: 99999999");
  try {
    io::parse_bvh(bogus, "bogus.bvh", metres());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'Frames: 99999999' but the file has 2 motion lines"), std::string::npos);
  }
}

TEST(BvhErrors, JointsWithoutChannelsCannotMultiplyTheFrameCount) {
  // 500 joints with no channels under a 1-channel root and 20,000 one-value
  // lines (a 50 KB file) declared 10 M joint poses (560 MB) before the fix;
  // the bound now follows the file's size.
  std::string text = "HIERARCHY\nROOT r\n{\nOFFSET 0 0 0\nCHANNELS 1 Yrotation\n";
  for (int i = 0; i < 500; ++i) text += "JOINT j" + std::to_string(i) + "\n{\nOFFSET 0 1 0\nCHANNELS 0\n}\n";
  text += "}\nMOTION\nFrames: 20000\nFrame Time: 0.01\n";
  for (int i = 0; i < 20000; ++i) text += "0\n";
  try {
    io::parse_bvh(text, "wide.bvh", metres());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("wide.bvh:", 0), 0u) << msg;
    EXPECT_NE(msg.find("20000 frames x 501 joints is more than legwork reads from a"), std::string::npos) << msg;
  }
  // The same skeleton with a plausible number of frames reads.
  std::string few = text.substr(0, text.find("Frames: 20000")) + "Frames: 100\nFrame Time: 0.01\n";
  for (int i = 0; i < 100; ++i) few += "0\n";
  EXPECT_EQ(io::parse_bvh(few, "wide.bvh", metres()).motion.frame_count(), 100);
}

TEST(BvhErrors, Utf16TextIsNamed) {
  // Windows tools save "Unicode" as UTF-16: say so instead of "found '??H?I?'".
  std::string le = "\xFF\xFE";
  for (char c : kValid) le += c, le += '\0';
  std::string be = "\xFE\xFF";
  for (char c : kValid) be += '\0', be += c;
  std::string bare;  // no byte-order mark
  for (char c : kValid) bare += c, bare += '\0';
  for (const auto& text : {le, be, bare}) {
    try {
      io::parse_bvh(text, "wide.bvh", metres());
      ADD_FAILURE() << "expected an error";
    } catch (const Error& e) {
      EXPECT_STREQ(e.what(), "wide.bvh: UTF-16 text; save it as UTF-8");
    }
  }
}

TEST(BvhErrors, Utf8ByteOrderMarkIsAccepted) {
  const auto f = io::parse_bvh("\xEF\xBB\xBF" + kValid, "bom.bvh", metres());
  EXPECT_EQ(f.motion.frame_count(), 2);
}

TEST(BvhErrors, UnicodeJointNamesAreKept) {
  const auto f = io::parse_bvh(replace(kValid, "JOINT Spine", "JOINT Wirbels\xC3\xA4ule"), "utf8.bvh", metres());
  EXPECT_EQ(f.motion.skeleton.names[1], "Wirbels\xC3\xA4ule");
}
