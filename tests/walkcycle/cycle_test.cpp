// The walk cycle (cycle.cpp): mirroring, loop continuity, key poses hit, shift.
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
using namespace legwork::walkcycle::samples;

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
