// Walk-cycle generator: key-pose files, mirroring, loop continuity, no-slip
// walking (straight and curved), paths, shift, reproducibility, bad input.
#include <legwork/core/fk.hpp>
#include <legwork/core/mirror.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/measure.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <cstdio>

using namespace legwork;
using namespace legwork::walkcycle;

namespace {

const Skeleton& cmu_skeleton() { return testdata::sample_skeleton(); }

std::string walk_file(const std::string& name) { return testdata::walk_keys_file(name); }

const std::vector<std::string> kWalks{"normal", "sneak", "double-bounce"};

CycleModel shipped(const std::string& name) { return build_cycle(cmu_skeleton(), read_walk_keys(walk_file(name), cmu_skeleton())); }

// A 90-degree left turn: straight 2 m, a quarter circle of radius 3 m, straight 2 m.
Path quarter_turn() {
  return parse_path_json(R"({"bezier": [[0,0],[0,0.7],[0,1.3],[0,2],
                                        [0,3.657],[1.343,5],[3,5],
                                        [3.7,5],[4.3,5],[5,5]]})",
                         "quarter-turn");
}

double rotation_distance(const Quat& a, const Quat& b) { return 1.0 - std::abs(a.coeffs().dot(b.coeffs())); }

std::string expect_error(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected legwork::Error";
  return "";
}

}  // namespace

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

TEST(Paths, FormatsAndBadPaths) {
  const Path poly = parse_path_json(R"({"polyline": [[0,0],[0,1],[1,1]]})", "p");
  EXPECT_NEAR(poly.length(), 2.0, 1e-12);
  EXPECT_NEAR(poly.total_turning(), kPi / 2, 1e-12);
  const Path svg = parse_svg_path("M 0 0 L 0 2 C 0 3 1 4 2 4", "svg");
  EXPECT_NEAR(svg.points.back().x(), 2.0, 1e-12);
  EXPECT_NEAR(svg.points.back().z(), 4.0, 1e-12);
  const Path rel = parse_svg_path("m 0 0 l 0 2 h 1 v 1", "svg");
  EXPECT_NEAR(rel.length(), 4.0, 1e-12);
  const Path cr = parse_path_json(R"({"catmull_rom": [[0,0],[0,2],[2,3]]})", "c");
  EXPECT_NEAR(cr.points.back().x(), 2.0, 1e-12);
  EXPECT_NEAR(quarter_turn().total_turning(), kPi / 2, 0.02);

  auto msg = expect_error([] { parse_path_json(R"({"polyline": []})", "empty.json"); });
  EXPECT_NE(msg.find("empty"), std::string::npos) << msg;
  msg = expect_error([] { parse_path_json(R"({"polyline": [[0,0],[1,1],[1,1],[2,2]]})", "rep.json"); });
  EXPECT_NE(msg.find("point 2 repeats point 1"), std::string::npos) << msg;
  msg = expect_error([] { parse_svg_path("", "svg"); });
  EXPECT_NE(msg.find("empty"), std::string::npos) << msg;
  msg = expect_error([] { parse_svg_path("M 0 0 A 1 1 0 0 1 2 2", "svg"); });
  EXPECT_NE(msg.find("unsupported command 'A'"), std::string::npos) << msg;
  msg = expect_error([] { parse_path_json(R"({"bezier": [[0,0],[0,1],[0,2]]})", "b.json"); });
  EXPECT_NE(msg.find("3n+1"), std::string::npos) << msg;
}

// The CMU skeleton with its left and right bones made mirror images (mean of
// both sides), so mirrored poses give exactly mirrored positions.
Skeleton symmetric(const Skeleton& in) {
  Skeleton s = in;
  for (int j = 0; j < s.joint_count(); ++j) {
    const auto ju = static_cast<std::size_t>(j), mu = static_cast<std::size_t>(in.mirror[ju]);
    s.rest_offsets[ju] = 0.5 * (in.rest_offsets[ju] + mirror_vector(in.rest_offsets[mu]));
    s.end_sites[ju] = 0.5 * (in.end_sites[ju] + mirror_vector(in.end_sites[mu]));
  }
  return s;
}

TEST(Cycle, SecondStepIsTheMirroredFirstStep) {
  const Skeleton sym = symmetric(cmu_skeleton());
  for (const auto& w : kWalks) {
    for (bool with_shift : {false, true}) {
      auto keys = read_walk_keys(walk_file(w), sym);
      if (!with_shift) keys.shift.clear();
      const CycleModel m = build_cycle(sym, keys);
      const double half = m.half_cycle();
      Pose a(sym), b(sym), mirrored(sym);
      double worst_rot = 0, worst_pos = 0;
      for (double t = 0; t < half; t += 0.25) {
        sample_cycle(m, t, a.ref());
        sample_cycle(m, t + half, b.ref());
        mirror_pose(sym, a, mirrored.ref());
        for (int j = 0; j < sym.joint_count(); ++j) {
          worst_rot = std::max(worst_rot, rotation_distance(b.rotations[static_cast<std::size_t>(j)], mirrored.rotations[static_cast<std::size_t>(j)]));
          worst_pos = std::max(worst_pos, (b.translations[static_cast<std::size_t>(j)] - mirrored.translations[static_cast<std::size_t>(j)]).norm());
        }
      }
      EXPECT_LT(worst_rot, 1e-12) << w;
      EXPECT_LT(worst_pos, 1e-12) << w;
      if (!with_shift) {
        // The next contact (frame N/2) is the mirrored contact key.
        sample_cycle(m, half, b.ref());
        for (int j = 0; j < sym.joint_count(); ++j)
          EXPECT_LT(rotation_distance(b.rotations[static_cast<std::size_t>(j)], m.step_keys[4].rotations[static_cast<std::size_t>(j)]), 1e-12)
              << w << " " << sym.names[static_cast<std::size_t>(j)];
      }
      // Left-hand arc of step 2 = mirrored right-hand arc of step 1.
      const Arc left = trace_arc(m, sym.find("LeftHand"), 2), right = trace_arc(m, sym.find("RightHand"), 2);
      const int n = static_cast<int>(left.points.size());
      double arc_err = 0;
      for (int i = 0; i < n / 2; ++i)
        arc_err = std::max(arc_err, (left.points[static_cast<std::size_t>(i + n / 2)] - mirror_vector(right.points[static_cast<std::size_t>(i)])).norm());
      EXPECT_LT(arc_err, 1e-9) << w;
    }
  }
  // On the real (slightly asymmetric) CMU skeleton the arcs differ only by
  // the bone-length asymmetry (a few centimetres), the rotations not at all.
  const CycleModel m = shipped("normal");
  const Arc left = trace_arc(m, m.skeleton.find("LeftHand")), right = trace_arc(m, m.skeleton.find("RightHand"));
  double err = 0;
  for (int i = 0; i < 12; ++i) err = std::max(err, (left.points[static_cast<std::size_t>(i + 12)] - mirror_vector(right.points[static_cast<std::size_t>(i)])).norm());
  std::printf("[walkcycle] CMU skeleton: left-hand arc of step 2 vs mirrored right-hand arc of step 1: %.1f mm (bone asymmetry)\n", err * 1000);
  EXPECT_LT(err, 0.04);
}

TEST(Cycle, KeysAreHitAndTheLoopIsContinuous) {
  const auto& s = cmu_skeleton();
  for (const auto& w : kWalks) {
    auto keys = read_walk_keys(walk_file(w), s);
    keys.shift.clear();  // with no shift and no floor lift every key pose is hit exactly
    keys.floor_clamp = false;
    const CycleModel m = build_cycle(s, keys);
    Pose p(s);
    for (int k = 0; k < kKeyCount; ++k) {
      sample_cycle(m, m.key_frames[static_cast<std::size_t>(k)], p.ref());
      for (int j = 0; j < s.joint_count(); ++j)
        EXPECT_LT(rotation_distance(p.rotations[static_cast<std::size_t>(j)], m.step_keys[static_cast<std::size_t>(k)].rotations[static_cast<std::size_t>(j)]), 1e-12);
      EXPECT_NEAR((p.translations[0] - m.step_keys[static_cast<std::size_t>(k)].translations[0]).norm(), 0.0, 1e-12);
    }
    for (const CycleModel& mm : {m, shipped(w)}) {  // without and with the walk's shift
      const SeamReport seam = measure_loop_seam(mm);
      std::printf("[walkcycle] %-13s loop seam: position %.2e m, velocity %.2e m/s\n", w.c_str(), seam.position_m, seam.velocity_mps);
      EXPECT_LT(seam.position_m, 1e-4) << w;
      EXPECT_LT(seam.velocity_mps, 1e-4) << w;
    }
    // Key poses keep the feet on the floor ("height": "floor"), and the
    // floor lift keeps them from dipping below it between the keys.
    for (double h : key_foot_heights(m)) EXPECT_NEAR(h, 0.0, 0.005) << w;
    const CycleModel lifted = shipped(w);
    const FloorReport fl = cycle_floor_contact(lifted);
    const auto at_keys = key_foot_heights(lifted);  // the lift may raise a key a little
    for (int k = 0; k < kKeyCount; ++k) {
      sample_cycle(lifted, lifted.key_frames[static_cast<std::size_t>(k)], p.ref());
      EXPECT_LT(lowest_foot_height(lifted, p), 0.01) << w << " key " << k;  // floats at most 1 cm at a key
    }
    (void)at_keys;
    std::printf("[walkcycle] %-13s feet: a foot would dip %.1f mm below the floor between keys (frame %.2f); with the lift, lowest %.2f mm\n",
                w.c_str(), fl.max_lift_m * 1e3, fl.lift_frame, fl.lowest_m * 1e3);
    EXPECT_GT(fl.lowest_m, -1e-3) << w;
  }
}

TEST(Cycle, ShiftDelaysAJointCyclically) {
  const auto& s = cmu_skeleton();
  auto keys = read_walk_keys(walk_file("normal"), s);
  keys.shift.clear();
  const CycleModel plain = build_cycle(s, keys);
  keys.shift = parse_shift_spec("LeftArm=2.5", s);
  const CycleModel shifted = build_cycle(s, keys);
  Pose a(s), b(s);
  const int la = s.find("LeftArm"), ra = s.find("RightArm"), lf = s.find("LeftForeArm");
  for (double t = 0; t < 24; t += 0.5) {
    sample_cycle(plain, t, a.ref());
    sample_cycle(shifted, t + 2.5, b.ref());  // wraps past the seam for t > 21.5
    EXPECT_LT(rotation_distance(a.rotations[static_cast<std::size_t>(la)], b.rotations[static_cast<std::size_t>(la)]), 1e-12) << t;
    EXPECT_LT(rotation_distance(a.rotations[static_cast<std::size_t>(ra)], b.rotations[static_cast<std::size_t>(ra)]), 1e-12) << t;  // mirrored joint too
    sample_cycle(shifted, t, b.ref());
    EXPECT_LT(rotation_distance(a.rotations[static_cast<std::size_t>(lf)], b.rotations[static_cast<std::size_t>(lf)]), 1e-12) << t;  // others untouched
  }
  EXPECT_LT(measure_loop_seam(shifted).velocity_mps, 1e-4);
}

TEST(Walk, StanceFootDoesNotSlipStraightOrCurved) {
  for (const auto& w : kWalks) {
    const CycleModel m = shipped(w);
    const double L = step_length(m);
    EXPECT_GT(L, 0.3) << w;
    const WalkResult straight = walk_path(m, straight_path(8.0));
    const SlipReport s1 = measure_stance_slip(m, straight.motion, straight.labels);
    const WalkResult curved = walk_path(m, quarter_turn());
    const SlipReport s2 = measure_stance_slip(m, curved.motion, curved.labels);
    std::printf("[walkcycle] %-13s step %.3f m | straight 8 m: %d steps, slip max %.2e mm | 90-degree path: %d steps, turned %.1f deg, "
                "slip max %.2e mm, deviation %.3f m, end %.3f m\n",
                w.c_str(), L, straight.steps, s1.max_mm, curved.steps, rad2deg(curved.turning), s2.max_mm,
                curved.max_path_deviation, curved.end_distance);
    EXPECT_LE(s1.max_mm, 1.0) << w;
    EXPECT_LE(s2.max_mm, 2.0) << w;
    EXPECT_GT(s1.phases, 10) << w;
    // It really walks: 8 m forward along +z; the curved walk turns by about 90 degrees.
    const Vec3 end1 = straight.motion.frame(straight.motion.frame_count() - 1).translations[0];
    EXPECT_NEAR(end1.z(), 8.0, L) << w;
    EXPECT_NEAR(std::abs(rad2deg(curved.turning)), 90.0, 12.0) << w;
    EXPECT_LT(curved.end_distance, L) << w;
    EXPECT_LT(curved.max_path_deviation, 0.15) << w;
    EXPECT_LT(straight.max_path_deviation, 0.12) << w;
  }
}

TEST(Walk, SlipMeasureCatchesASlidingFoot) {
  // The same cycle pushed forward at constant speed (no pivoting) slides.
  const CycleModel m = shipped("normal");
  const double L = step_length(m);
  Motion naive = bake_cycle(m);
  Motion longer(m.skeleton, m.fps, 0);
  std::vector<FrameLabel> labels;
  for (int f = 0; f < 3 * m.frames_per_cycle; ++f) {
    Pose p(m.skeleton);
    sample_cycle(m, f, p.ref());
    p.translations[0].z() += L * f / m.half_cycle();
    longer.push_back(p);
    const StanceAt s = stance_at(m, std::max(0.0, f - 0.5));
    labels.push_back({s.step, s.left, s.pivot, false});
  }
  const SlipReport r = measure_stance_slip(m, longer, labels);
  std::printf("[walkcycle] constant-speed root (no pivoting): slip max %.1f mm\n", r.max_mm);
  EXPECT_GT(r.max_mm, 10.0);
}

TEST(Walk, StopsInTheStandingPose) {
  const CycleModel m = shipped("normal");
  const WalkResult w = walk_path(m, straight_path(5.0));
  const int last = w.motion.frame_count() - 1;
  const auto pose = w.motion.frame(last);
  for (int j = 1; j < m.skeleton.joint_count(); ++j)
    EXPECT_LT(rotation_distance(pose.rotations[static_cast<std::size_t>(j)], m.stand.rotations[static_cast<std::size_t>(j)]), 1e-9);
  // Both feet on the floor, side by side.
  const auto pos = joint_positions(m.skeleton, pose);
  const Vec3 la = pos[static_cast<std::size_t>(m.left.ankle)], ra = pos[static_cast<std::size_t>(m.right.ankle)];
  EXPECT_LT(std::abs(la.z() - ra.z()), 0.1);
  EXPECT_TRUE(w.labels.back().stopping);
}

TEST(Walk, SameInputSameBytes) {
  const CycleModel m1 = shipped("double-bounce");
  const CycleModel m2 = shipped("double-bounce");
  const auto a = io::format_bvh(walk_path(m1, quarter_turn(), {}).motion);
  const auto b = io::format_bvh(walk_path(m2, quarter_turn(), {}).motion);
  EXPECT_EQ(a, b);
  EXPECT_GT(a.size(), 10000u);
  EXPECT_EQ(format_walk_keys(read_walk_keys(walk_file("sneak"), cmu_skeleton()), cmu_skeleton()),
            format_walk_keys(read_walk_keys(walk_file("sneak"), cmu_skeleton()), cmu_skeleton()));
}

TEST(Walk, RetimeKeepsThePhaseOfTheKeys) {
  const auto& s = cmu_skeleton();
  const auto keys = read_walk_keys(walk_file("normal"), s);
  const CycleModel m24 = build_cycle(s, keys);
  const CycleModel m32 = build_cycle(s, retime(keys, 32));
  EXPECT_EQ(m32.frames_per_cycle, 32);
  EXPECT_DOUBLE_EQ(m32.key_frames[2], 8.0);
  EXPECT_NEAR(step_length(m24), step_length(m32), 1e-3);  // same poses, same stride
}

TEST(Arcs, AJerkyKeyPoseShowsInTheArc) {
  const auto& s = cmu_skeleton();
  auto keys = read_walk_keys(walk_file("normal"), s);
  keys.shift.clear();
  keys.floor_clamp = false;  // the arm alone
  const CycleModel smooth = build_cycle(s, keys);
  // Flick the left elbow at the down key only.
  keys.keys[1].set(s.find("LeftForeArm"), euler_xyz_to_quat(Vec3(0, -95, 0), keys.euler));
  const CycleModel jerky = build_cycle(s, keys);
  const auto a = arc_smoothness(trace_arc(smooth, s.find("LeftHand"), 4));
  const auto b = arc_smoothness(trace_arc(jerky, s.find("LeftHand"), 4));
  std::printf("[walkcycle] LeftHand arc jerk ratio: smooth %.2f, jerky key %.2f (at frame %.1f)\n", a.jerk_ratio, b.jerk_ratio, b.jerk_frame);
  EXPECT_GT(b.jerk_ratio, a.jerk_ratio * 1.3);
  EXPECT_NEAR(b.jerk_frame, keys.key_frames[1], 2.0);
}
