// The server's methods without a server: which methods a resource set
// offers, option checks with the client-facing messages, and the ik / wip /
// combined methods driven straight by a real trial's trackers.
#include <legwork/serve/methods.hpp>

#include <legwork/core/fk.hpp>
#include <legwork/core/limits.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/io/bvh.hpp>

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "cmu_sample.hpp"
#include "error_message.hpp"

namespace legwork::serve {
using legwork::testdata::message_of;

namespace {

// The avatar skeleton (CMU subject 7) and head + hands (+ ankles) of another trial of the same subject.
const Skeleton& avatar() { return testdata::sample_skeleton(); }
std::vector<TrackerFrame> trial(bool feet) {
  auto frames = tracker_frames_from_motion(testdata::load_sample("cmu/bvh/walking/07_02.bvh"), 90.0);
  if (!feet)
    for (auto& f : frames) f.foot(kLeft).valid = f.foot(kRight).valid = false;
  return frames;
}

Resources skeleton_only() {
  Resources r;
  r.skeleton = &avatar();
  return r;
}

MethodOptions options(const std::string& method) {
  MethodOptions o;
  o.method = method;
  return o;
}

const InfoFields::Item* find_info(const InfoFields& info, const char* key) {
  for (int i = 0; i < info.count; ++i)
    if (std::strcmp(info.items[static_cast<std::size_t>(i)].key, key) == 0) return &info.items[static_cast<std::size_t>(i)];
  return nullptr;
}

TEST(ServeMethods, AvailableMethodsFollowTheResources) {
  EXPECT_EQ(known_methods(), (std::vector<std::string>{"accent", "ik", "wip", "combined", "walker"}));
  EXPECT_TRUE(available_methods(Resources{}).empty());
  EXPECT_EQ(available_methods(skeleton_only()), (std::vector<std::string>{"ik", "wip", "combined"}));
  Resources walks;
  walks.walks_dir = "walks";
  EXPECT_EQ(available_methods(walks), (std::vector<std::string>{"walker"}));
}

TEST(ServeMethods, BadOptionsAreExplainedToTheClient) {
  const Resources res = skeleton_only();
  EXPECT_EQ(message_of([&] { make_method(res, options("dance")); }),
            "unknown method 'dance' (known: accent, ik, wip, combined, walker)");
  EXPECT_EQ(message_of([&] { make_method(res, options("accent")); }),
            "method 'accent' needs a database: start the server with --db FILE");
  EXPECT_EQ(message_of([&] { make_method(Resources{}, options("ik")); }),
            "method 'ik' is not available in this server (available: )");
  MethodOptions o = options("ik");
  o.exaggeration = 0;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "exaggeration 0.000000 is outside (0, 4]");
  o.exaggeration = 4;  // the upper bound is allowed
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "(no error)");
  o.foot_lift_height = 0.8;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "foot_lift_height 0.800000 m is outside [0, 0.5]");
  o.foot_lift_height = 0.1;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "(no error)");
  o.foot_lock_slack = 1.5;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "foot_lock_slack 1.500000 m is outside [0, 1]");
  o.foot_lock_slack = 0.2;
  o.foot_lock_hold_seconds = -0.5;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "foot_lock_hold_seconds -0.500000 s is outside [0, 10]");
  o.foot_lock_hold_seconds = 0.3;
  o.foot_swing_speed = -1;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "foot_swing_speed -1.000000 m/s is outside [0, 10]");
  o.foot_swing_speed = 0.8;
  o.travel_weight = -2;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "travel_weight -2.000000 is outside [0, 100] (0 = off)");
  o.travel_weight = 4;
  o.max_head_height_diff = 3;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "max_head_height_diff 3.000000 is outside [0, 2] (0 = off)");
  o.max_head_height_diff = 0.2;
  o.smooth_feedforward = 2;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "smooth_feedforward 2.000000 is outside [0, 1] (0 = off)");
  o.smooth_feedforward = 0.5;
  o.lying_root_smoothing = 0;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "lying_root_smoothing 0.000000 is outside [1, 20] (1 = off)");
  o.lying_root_smoothing = 2;
  o.lying_crown = -1;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "lying_crown -1.000000 is outside [0, 1] (0 = off)");
  o.lying_crown = 0.5;
  o.other_class_cost = 0.5;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "other_class_cost 0.500000 is neither 0 (off) nor in [1, 1e6]");
  o.other_class_cost = 0;
  o.search_interval = -0.5;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "search_interval -0.500000 is outside [0, 1] seconds (0 = every frame)");
  o.search_interval = 0;
  o.floor_height = 12;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "floor_height 12.000000 m is outside [-10, 10]");
  o.floor_height = -0.5;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "(no error)");
  o.user_height = 9;
  char want[160];
  std::snprintf(want, sizeof want, "user_height 9.000000 m is outside [%g, %g] (0 = the avatar's own)", kMinUserHeight,
                kMaxUserHeight);
  EXPECT_EQ(message_of([&] { make_method(res, o); }), want);
}

TEST(ServeMethods, UserHeightScalesTheAvatar) {
  const double own = measure_body(avatar()).standing_height;
  EXPECT_EQ(measure_body(make_method(skeleton_only(), options("ik"))->skeleton()).standing_height, own);
  for (const char* m : {"ik", "wip", "combined"}) {
    MethodOptions o = options(m);
    o.user_height = 1.5;
    const auto method = make_method(skeleton_only(), o);
    EXPECT_NEAR(measure_body(method->skeleton()).standing_height, 1.5, 1e-9) << m;
    EXPECT_EQ(method->skeleton().joint_count(), avatar().joint_count()) << m;
  }
}

TEST(ServeMethods, IkWristsReachTheTrackedHands) {
  const auto method = make_method(skeleton_only(), options("ik"));
  const Skeleton& skel = method->skeleton();
  const int hand[2] = {skel.require("LeftHand"), skel.require("RightHand")};
  Pose pose(skel);
  std::vector<Vec3> world(static_cast<std::size_t>(skel.joint_count()));
  double worst = 0;
  for (const TrackerFrame& f : trial(false)) {
    InfoFields info;
    ASSERT_EQ(method->update(f, pose.ref(), info), UpdateStatus::Ok);
    ASSERT_NE(find_info(info, "head_tracked"), nullptr);
    EXPECT_EQ(find_info(info, "head_tracked")->number, 1.0);
    forward_positions(skel, pose.ref(), world);
    for (int s = 0; s < 2; ++s) worst = std::max(worst, (world[static_cast<std::size_t>(hand[s])] - f.hand(s).position).norm());
  }
  EXPECT_LT(worst, 0.01) << "wrists must be within 1 cm of the input hands";
}

TEST(ServeMethods, ARejectedFrameLeavesThePoseAlone) {
  const auto method = make_method(skeleton_only(), options("ik"));
  const auto frames = trial(false);
  Pose pose(method->skeleton());
  InfoFields info;
  ASSERT_NE(method->update(frames[5], pose.ref(), info), UpdateStatus::Rejected);
  const Pose before = pose;
  InfoFields again;
  EXPECT_EQ(method->update(frames[2], pose.ref(), again), UpdateStatus::Rejected);  // earlier time
  EXPECT_EQ(again.count, 0);  // no diagnostics for a frame not consumed
  for (int j = 0; j < method->skeleton().joint_count(); ++j) {
    EXPECT_EQ(pose.rotations[static_cast<std::size_t>(j)].coeffs(), before.rotations[static_cast<std::size_t>(j)].coeffs());
    EXPECT_EQ(pose.translations[static_cast<std::size_t>(j)], before.translations[static_cast<std::size_t>(j)]);
  }
}

TEST(ServeMethods, WipAndCombinedDescribeTheirLegs) {
  const auto frames = trial(true);
  for (const char* m : {"wip", "combined"}) {
    SCOPED_TRACE(m);
    const auto method = make_method(skeleton_only(), options(m));
    Pose pose(method->skeleton());
    int walking = 0;
    double distance = 0;
    for (const TrackerFrame& f : frames) {
      InfoFields info;
      ASSERT_NE(method->update(f, pose.ref(), info), UpdateStatus::Rejected);
      const auto* w = find_info(info, "walking");
      const auto* d = find_info(info, "distance");
      ASSERT_NE(w, nullptr);
      ASSERT_NE(d, nullptr);
      walking += w->number > 0;
      EXPECT_GE(d->number, distance);  // distance walked never shrinks
      distance = d->number;
    }
    EXPECT_GT(walking, 0) << "the legs never walked on a real walk's ankles";
    EXPECT_GT(distance, 0.0);
  }
  // The combined method says where its legs come from: wip while the feet are tracked.
  const auto combined = make_method(skeleton_only(), options("combined"));
  Pose pose(combined->skeleton());
  InfoFields info;
  combined->update(frames[0], pose.ref(), info);
  ASSERT_NE(find_info(info, "legs"), nullptr);
  EXPECT_STREQ(find_info(info, "legs")->text, "wip");
}

// A walker method driven 5 s at 30 Hz with the head still (it walks on its own): the root at the
// end, and the root's height at the first frame in `first`.
Vec3 walk_five_seconds(Method& method, double& first) {
  Pose pose(method.skeleton());
  InfoFields info;
  for (int f = 0; f < 150; ++f) {
    TrackerFrame frame;
    frame.time = f / 30.0;
    frame.head() = {Vec3(0, 1.7, 0), Quat::Identity(), true};
    EXPECT_EQ(method.update(frame, pose.ref(), info), UpdateStatus::Ok);
    if (f == 0) first = pose.translations[0].y();
  }
  return pose.translations[0];
}

}  // namespace
// The walker method: a shipped walk steered by the head's yaw, its root
// smooth by default and pivoting on request (hello "walk", "root"), bad
// names explained.
TEST(ServeMethods, WalkerWalksAShippedWalkWithTheRootAsked) {
  Resources res;
  res.walks_dir = std::string(LEGWORK_SOURCE_DIR) + "/data/walks";
  MethodOptions o = options("walker");
  o.walk = "strut";
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "walk 'strut' is not one of this server's walks (double-bounce, normal, sneak)");
  o.walk = "sneak";
  o.root = "bouncy";
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "root 'bouncy' is not one of: smooth, pivot");
  double spread[2] = {0, 0};  // (max - min) / mean of the root's horizontal speed after the first second
  for (int k = 0; k < 2; ++k) {
    o.root = k == 0 ? "smooth" : "pivot";
    const auto method = make_method(res, o);
    Pose pose(method->skeleton());
    InfoFields info;
    Vec3 prev = Vec3::Zero();
    double lo = 1e9, hi = 0, sum = 0;
    int n = 0;
    for (int f = 0; f < 150; ++f) {
      TrackerFrame frame;
      frame.time = f / 30.0;
      frame.head() = {Vec3(0, 1.7, 0), Quat::Identity(), true};
      info = InfoFields{};
      ASSERT_EQ(method->update(frame, pose.ref(), info), UpdateStatus::Ok);
      const Vec3 root(pose.translations[0].x(), 0, pose.translations[0].z());
      const double speed = (root - prev).norm() * 30.0;
      if (f > 30) lo = std::min(lo, speed), hi = std::max(hi, speed), sum += speed, ++n;
      prev = root;
    }
    spread[k] = (hi - lo) / (sum / n);
    ASSERT_NE(find_info(info, "pivot"), nullptr);
    ASSERT_NE(find_info(info, "reach_limited"), nullptr);
    EXPECT_EQ(find_info(info, "reach_limited")->number, 0.0);
    EXPECT_GT(prev.z(), 2.0);  // walked forward
  }
  std::printf("[serve] walker sneak root speed spread: smooth %.3f, pivot %.3f of the mean\n", spread[0], spread[1]);
  EXPECT_LT(spread[0], 0.4);  // within +-20 %
  EXPECT_GT(spread[1], 0.4);
}

// The walker on the ground of hello "ground" (a path file's "ground"): up a
// 10 % slope the root rises with it; a bad ground names the hello field.
TEST(ServeMethods, WalkerWalksTheHellosGround) {
  Resources res;
  res.walks_dir = std::string(LEGWORK_SOURCE_DIR) + "/data/walks";
  MethodOptions o = options("walker");
  o.ground = R"({"slope": {"origin": [0, 0.5], "direction": [0, 1], "grade": 0.1}})";
  const auto method = make_method(res, o);
  double first = 0;
  const Vec3 end = walk_five_seconds(*method, first);
  EXPECT_GT(end.z(), 4.0);
  // As high above the ground as at the start (the pelvis follows the lower foot: up to half a stride's rise below).
  EXPECT_NEAR(end.y() - 0.1 * (end.z() - 0.5), first, 0.1 * 0.36 + 0.01);
  o.ground = R"({"slope": {"origin": [0, 0.5], "direction": [0, 1], "grade": 0.9}})";
  EXPECT_NE(message_of([&] { make_method(res, o); }).find("hello.ground: slope: grade 0.900000"), std::string::npos);
}

// `legwork serve`'s walker up the stairs of hello "ground" (the shipped
// stairs.json's: 5 x 0.15 m from z = 1.5 m): it ends on the landing, 0.75 m
// up, as high above it as it started above the floor (within the step's bob).
TEST(ServeMethods, WalkerClimbsTheHellosStairs) {
  Resources res;
  res.walks_dir = std::string(LEGWORK_SOURCE_DIR) + "/data/walks";
  MethodOptions o = options("walker");
  o.ground = R"({"stairs": {"origin": [0, 1.5], "direction": [0, 1], "rise": 0.15, "run": 0.36, "count": 5}})";
  const auto method = make_method(res, o);
  double first = 0;
  const Vec3 end = walk_five_seconds(*method, first);
  std::printf("[serve] walker up the stairs: root %.3f m above the floor at the start, %.3f m above the landing at z %.2f m\n", first,
              end.y() - 0.75, end.z());
  EXPECT_GT(end.z(), 1.5 + 5 * 0.36);  // past the last riser
  EXPECT_NEAR(end.y() - 0.75, first, 0.03);
}

// The hello's walker settings reach the walker: on the same stairs a slower
// stairs_cadence gets less far in 5 s (the flight is climbed at that share of
// the cycle's rate); out-of-range values are refused with the walker's message.
TEST(ServeMethods, WalkerSettingsFromTheHello) {
  Resources res;
  res.walks_dir = std::string(LEGWORK_SOURCE_DIR) + "/data/walks";
  MethodOptions o = options("walker");
  o.ground = R"({"stairs": {"origin": [0, 1.0], "direction": [0, 1], "rise": 0.15, "run": 0.36, "count": 12}})";
  double reached[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    o.stairs_cadence = k == 0 ? 1.0 : 0.5;
    double first = 0;
    reached[k] = walk_five_seconds(*make_method(res, o), first).z();
  }
  std::printf("[serve] walker on 12 stairs in 5 s: z %.2f m at stairs_cadence 1, %.2f m at 0.5\n", reached[0], reached[1]);
  EXPECT_GT(reached[0], reached[1] + 0.5);
  o.stairs_cadence = 0;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "walker: stairs_cadence must be in (0, 1] (a fraction of the cycle's rate), got 0.000000");
  o.stairs_cadence = 0.8;
  o.soft_reach = 1.5;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "walker: soft_reach must be in (0, 1] (a fraction of the leg's length), got 1.500000");
  o.soft_reach = 0.98;
  o.max_turn_per_step = -1;
  EXPECT_EQ(message_of([&] { make_method(res, o); }), "walker: max_turn_per_step must be a finite angle >= 0 (radians), got -1.000000");
}

}  // namespace legwork::serve
