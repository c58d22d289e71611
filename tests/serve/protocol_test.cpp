// Protocol v1 messages without sockets: binary forms, JSON frames, bad input.
#include <legwork/serve/protocol.hpp>
#include <legwork/accent/accent.hpp>

#include "cmu_sample.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace legwork::serve {
namespace {

std::span<const std::byte> bytes(const std::string& s) { return std::as_bytes(std::span(s.data(), s.size())); }

TEST(Protocol, BinaryAndJsonFramesRoundTripARealFrame) {
  const auto frames = tracker_frames_from_motion(testdata::load_sample("cmu/bvh/walking/07_02.bvh"), 90.0);
  TrackerFrame f = frames[40];
  f.foot(kRight).valid = false;
  const std::string bin = binary_frame(f);
  ASSERT_EQ(bin.size(), kBinaryFrameBytes);
  const TrackerFrame b = parse_binary_frame(bytes(bin));
  const TrackerFrame j = parse_text(json_frame(f)).frame;
  EXPECT_EQ(b.time, f.time);
  for (int d = 0; d < kDeviceCount; ++d) {
    const auto i = static_cast<std::size_t>(d);
    EXPECT_EQ(b.devices[i].valid, f.devices[i].valid);
    EXPECT_EQ(j.devices[i].valid, f.devices[i].valid);
    if (!f.devices[i].valid) continue;
    EXPECT_LT((b.devices[i].position - f.devices[i].position).norm(), 1e-6);  // float32
    EXPECT_LT((j.devices[i].position - f.devices[i].position).norm(), 1e-5);  // 5 decimals
    EXPECT_LT(b.devices[i].rotation.angularDistance(f.devices[i].rotation), 1e-5);
  }
}

// Found by fuzz/protocol_fuzz.cpp: finite but absurd values must still make a
// unit rotation or an error, valid JSON and a binary form without a float
// overflow (undefined behaviour, caught by UBSan's float-cast-overflow).
TEST(Protocol, AbsurdButFiniteValuesKeepTheFormsValid) {
  // |q| overflows to Inf: it used to normalize to a zero quaternion marked valid.
  const TrackerFrame f = parse_text(R"({"type":"frame","t":1e300,"head":{"p":[1e300,-1e300,0],"q":[1e300,0,1e300,0]}})").frame;
  ASSERT_TRUE(f.head().valid);
  EXPECT_NEAR(f.head().rotation.norm(), 1.0, 1e-12);
  EXPECT_NEAR(f.head().rotation.w(), std::sqrt(0.5), 1e-12);
  EXPECT_FALSE(usable(f.head()));  // 1e300 m: lost tracking, not a pose
  // The JSON form used to append 48 bytes of a failed fixed-notation conversion.
  const std::string text = json_frame(f);
  EXPECT_NE(text.find("\"t\":1e+300"), std::string::npos) << text;
  const TrackerFrame back = parse_text(text).frame;
  EXPECT_EQ(back.time, 1e300);
  EXPECT_EQ(back.head().position.x(), 1e300);
  // The binary form saturates at the float range instead of overflowing.
  const TrackerFrame b = parse_binary_frame(bytes(binary_frame(f)));
  EXPECT_EQ(b.head().position.x(), std::numeric_limits<float>::max());
  EXPECT_EQ(b.head().position.y(), -std::numeric_limits<float>::max());
  EXPECT_FALSE(usable(b.head()));
}

TEST(Protocol, BinaryPoseLayout) {
  const Skeleton& skel = testdata::sample_skeleton();
  Pose p(skel);
  p.rotations[3] = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitX()));
  std::vector<Vec3> world(static_cast<std::size_t>(skel.joint_count()), Vec3(1, 2, 3));
  std::vector<int> joints{0, 3};
  PoseMessage m;
  m.seq = 17;
  m.t = 1.25;
  m.status = UpdateStatus::Degraded;
  m.pose = p.ref();
  m.world = world;
  m.joints = joints;
  std::string out;
  format_pose_binary(out, m);
  ASSERT_EQ(out.size(), kBinaryPoseHeaderBytes + 2 * 28);
  EXPECT_EQ(out.substr(0, 4), "LWP1");
  const BinaryPose b = parse_binary_pose(bytes(out));
  EXPECT_EQ(b.seq, 17u);
  EXPECT_EQ(b.t, 1.25);
  EXPECT_EQ(b.status, 1);
  EXPECT_NEAR(b.rotations[1].w(), std::cos(0.25), 1e-6);
  EXPECT_EQ(b.positions[1], Vec3(1, 2, 3));
}

// The no-class setting (accent::Settings::recognize_class) is a hello and an options field.
TEST(Protocol, RecognizeClassIsAHelloAndOptionsField) {
  EXPECT_TRUE(parse_text(R"({"type":"hello","version":1})").hello.method.recognize_class);  // the engine's default
  EXPECT_FALSE(parse_text(R"({"type":"hello","version":1,"recognize_class":false})").hello.method.recognize_class);
  const ClientMessage o = parse_text(R"({"type":"options","recognize_class":false})");
  ASSERT_TRUE(o.options.recognize_class.has_value());
  EXPECT_FALSE(*o.options.recognize_class);
  EXPECT_FALSE(parse_text(R"({"type":"options","exaggeration":2})").options.recognize_class.has_value());
}

// The planted feet's slack and the swing clearance's speed (accent::Settings::foot_lock_slack,
// foot_swing_speed) are hello fields; absent, the engine's defaults.
TEST(Protocol, FootSlackAndSwingSpeedAreHelloFields) {
  const auto absent = parse_text(R"({"type":"hello","version":1})").hello.method;
  EXPECT_EQ(absent.foot_lock_slack, accent::Settings{}.foot_lock_slack);
  EXPECT_EQ(absent.foot_swing_speed, accent::Settings{}.foot_swing_speed);
  const auto given = parse_text(R"({"type":"hello","version":1,"foot_lock_slack":0.2,"foot_swing_speed":0})").hello.method;
  EXPECT_EQ(given.foot_lock_slack, 0.2);
  EXPECT_EQ(given.foot_swing_speed, 0.0);
}

// The accentuation engine's numeric settings that are hello fields: absent, each
// is the engine's default (accent::Settings); given, the value sent.
TEST(Protocol, FloorIsAHelloField) {
  EXPECT_EQ(parse_text(R"({"type":"hello","version":1})").hello.method.floor, accent::Settings{}.floor);
  EXPECT_FALSE(parse_text(R"({"type":"hello","version":1,"floor":false})").hello.method.floor);
  try {
    parse_text(R"({"type":"hello","version":1,"floor":0})");
    ADD_FAILURE() << "a number for hello.floor was accepted";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code() + ": " + e.what(), "bad_message: hello.floor must be true or false");
  }
}

TEST(Protocol, AccentSettingsAreHelloFields) {
  struct Field {
    const char* name;
    double MethodOptions::*option;
    double engine_default, sent;
  };
  const accent::Settings d;
  for (const Field& f : {Field{"travel_weight", &MethodOptions::travel_weight, d.travel_weight, 4.5},  // the travel terms' weight
                         Field{"max_head_height_diff", &MethodOptions::max_head_height_diff, d.max_head_height_diff, 0.3},  // head-height gate
                         Field{"smooth_feedforward", &MethodOptions::smooth_feedforward, d.smooth_feedforward, 0.5},  // the candidates' motion played forward
                         Field{"lying_root_smoothing", &MethodOptions::lying_root_smoothing, d.lying_root_smoothing, 8},  // a lying user's root
                         Field{"lying_crown", &MethodOptions::lying_crown, d.lying_crown, 0.5},  // a lying user turned by the crown
                         Field{"other_class_cost", &MethodOptions::other_class_cost, d.other_class_cost, 1.5},  // other classes at a cost
                         Field{"search_interval", &MethodOptions::search_interval, d.search_interval, 0.1},  // searches every hop
                         Field{"floor_height", &MethodOptions::floor_height, d.floor_height, -1.5},  // where the floor is
                         Field{"foot_lift_height", &MethodOptions::foot_lift_height, d.foot_lift_height, 0.1},  // released feet's lift
                         Field{"foot_lock_hold_seconds", &MethodOptions::foot_lock_hold_seconds, d.foot_lock_hold_seconds, 0.35}}) {  // planted feet held
    SCOPED_TRACE(f.name);
    EXPECT_EQ(parse_text(R"({"type":"hello","version":1})").hello.method.*f.option, f.engine_default);
    for (double v : {0.0, f.sent}) {
      const std::string text = std::string(R"({"type":"hello","version":1,")") + f.name + "\":" + std::to_string(v) + "}";
      EXPECT_EQ(parse_text(text).hello.method.*f.option, v);
    }
  }
}

TEST(Protocol, WalkAndRootAreHelloFields) {
  const Hello d = parse_text(R"({"type":"hello","version":1})").hello;
  EXPECT_EQ(d.method.walk, "normal");
  EXPECT_EQ(d.method.root, "smooth");
  const Hello h = parse_text(R"({"type":"hello","version":1,"method":"walker","walk":"sneak","root":"pivot"})").hello;
  EXPECT_EQ(h.method.method, "walker");
  EXPECT_EQ(h.method.walk, "sneak");
  EXPECT_EQ(h.method.root, "pivot");
  EXPECT_EQ(d.method.ground, "");
  const Hello g = parse_text(R"({"type":"hello","version":1,"method":"walker","ground":{"slope":{"origin":[0,1],"direction":[0,1],"grade":0.1}}})").hello;
  EXPECT_EQ(g.method.ground, R"({"slope":{"direction":[0,1],"grade":0.1,"origin":[0,1]}})");
  // The walker's settings: absent, the walker's defaults; given, as sent (ranges are the walker's: ServeMethods).
  EXPECT_EQ(d.method.max_turn_per_step, walkcycle::Settings{}.max_turn_per_step);
  EXPECT_EQ(d.method.soft_reach, walkcycle::Settings{}.soft_reach);
  EXPECT_EQ(d.method.stairs_cadence, walkcycle::Settings{}.stairs_cadence);
  const Hello w =
      parse_text(R"({"type":"hello","version":1,"method":"walker","max_turn_per_step":0.2,"soft_reach":0.9,"stairs_cadence":0.5})").hello;
  EXPECT_EQ(w.method.max_turn_per_step, 0.2);
  EXPECT_EQ(w.method.soft_reach, 0.9);
  EXPECT_EQ(w.method.stairs_cadence, 0.5);
}

TEST(Protocol, BadMessagesNameTheProblem) {
  const auto message = [](const std::string& text) {
    try {
      parse_text(text);
    } catch (const ProtocolError& e) {
      return e.code() + ": " + e.what();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message("[1,2]"), "bad_json: message must be a JSON object with a \"type\"");
  EXPECT_EQ(message(R"({"type":"hello"})"), "bad_version: unsupported protocol version (missing): this server speaks version 1");
  EXPECT_EQ(message(R"({"type":"hello","version":1,"format":"xml"})"), "bad_value: hello.format must be \"json\" or \"binary\"");
  EXPECT_EQ(message(R"({"type":"hello","version":1,"recognize_class":"yes"})"),
            "bad_message: hello.recognize_class must be true or false");
  EXPECT_EQ(message(R"({"type":"hello","version":1,"root":1})"), "bad_message: hello.root must be a string");
  EXPECT_EQ(message(R"({"type":"hello","version":1,"stairs_cadence":"slow"})"), "bad_value: hello.stairs_cadence is not a number (got string)");
  EXPECT_EQ(message(R"({"type":"hello","version":1,"ground":"hill"})"),
            "bad_message: hello.ground must be an object (a path file's \"ground\": slope or heightfield)");
  EXPECT_EQ(message(R"({"type":"options","recognize_class":1})"), "bad_message: options.recognize_class must be true or false");
  EXPECT_EQ(message(R"({"type":"frame"})"), "bad_message: frame without \"t\" (seconds)");
  EXPECT_EQ(message(R"({"type":"frame","t":1,"left":{"p":[0,1,0],"q":[0,0,0,0]}})"),
            "bad_value: frame.left.q is not a rotation (zero length)");
  EXPECT_EQ(message(R"({"type":"frame","t":1,"left":null})"), "accepted");
  std::string bin(kBinaryFrameBytes, '\0');
  std::memcpy(bin.data(), "LWF2", 4);
  try {
    parse_binary_frame(bytes(bin));
    ADD_FAILURE();
  } catch (const ProtocolError& e) {
    EXPECT_STREQ(e.what(), "binary frame does not start with \"LWF1\"");
  }
}

}  // namespace
}  // namespace legwork::serve
