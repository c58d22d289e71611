// Smooth root motion (offline/root_motion.cpp): the window average it smooths
// with (lines kept, one-step repeats removed, the held end), and walks whose
// root travels evenly while the legs' IK keeps the feet planted.
#include <legwork/core/fk.hpp>
#include <legwork/walkcycle/offline/measure.hpp>
#include <legwork/walkcycle/offline/walk.hpp>

#include "../../src/walkcycle/offline/root_motion.hpp"
#include "testdata.hpp"
#include "walk_samples.hpp"

#include <cstdio>

using namespace legwork;
using namespace legwork::walkcycle;
using namespace legwork::walkcycle::samples;

namespace {

// a + b f for f = 0 .. n-1.
std::vector<Vec3> line(int n, const Vec3& a, const Vec3& b) {
  std::vector<Vec3> q;
  for (int f = 0; f < n; ++f) q.push_back(a + f * b);
  return q;
}

}  // namespace

TEST(RootMotion, WindowAverageKeepsStraightLines) {
  const Vec3 a(0.3, 1.0, -2), b(0.01, -0.002, 0.05);
  const auto q = line(40, a, b);
  for (double width : {1.0, 2.5, 8.0, 30.0, 100.0}) {
    // Extended at both ends at the line's own velocity, a line averages to itself.
    const auto out = window_average(q, width, false);
    ASSERT_EQ(out.size(), q.size());
    for (std::size_t f = 0; f < q.size(); ++f) EXPECT_LT((out[f] - q[f]).norm(), 1e-12) << width << " frame " << f;
  }
  // Nothing to average: the series as it is.
  EXPECT_EQ(window_average(q, 0, false), q);
  EXPECT_EQ(window_average(std::vector<Vec3>{a}, 5, true), std::vector<Vec3>{a});
}

TEST(RootMotion, WindowOfOneStepRemovesWhatRepeatsEveryStep) {
  // A line plus a zero-mean wobble repeating every 4 frames (a lunge and a stall per step).
  const Vec3 a(0, 0.9, 0), b(0, 0, 0.05);
  const double wobble[4] = {0.02, 0.01, -0.02, -0.01};
  auto q = line(48, a, b);
  for (std::size_t f = 0; f < q.size(); ++f) q[f].z() += wobble[f % 4];
  const auto out = window_average(q, 4.0, false);
  // Wherever the window lies inside the series, only the line is left.
  for (std::size_t f = 2; f + 2 < q.size(); ++f) EXPECT_LT((out[f] - (a + static_cast<double>(f) * b)).norm(), 1e-12) << f;
}

TEST(RootMotion, RestAtEndHoldsTheLastValueBeyondTheEnd) {
  const Vec3 a(1, 0, 0), b(0, 0, 0.04);
  const double w = 6;
  const auto q = line(30, a, b);
  const auto out = window_average(q, w, true);
  // The start still runs on at the line's velocity: unchanged there.
  EXPECT_LT((out.front() - q.front()).norm(), 1e-12);
  // At the last frame half the window is the held end: the mean of the line's
  // last half window and the end value, q.back() - b w / 8.
  EXPECT_LT((out.back() - (q.back() - b * (w / 8))).norm(), 1e-12);
  // The averaged root approaches the end without passing it.
  for (std::size_t f = 1; f < out.size(); ++f) {
    EXPECT_GE(out[f].z(), out[f - 1].z());
    EXPECT_LE(out[f].z(), q.back().z() + 1e-12);
  }
}

// Issue 14, item 1: the smooth root travels at an even speed, the stance
// foot stays planted (by the legs' IK, not by pushing the root) and no knee
// straightens past its length; the pivoting root (document 001) lunges and
// stalls on the same walk, which the same measures catch.
TEST(RootMotion, SmoothRootTravelsEvenlyWithTheFeetPlanted) {
  for (const auto& name : kWalks) {
    const CycleModel m = shipped(name);
    WalkOptions steady, pivot;
    steady.steps = pivot.steps = 10;
    pivot.root = RootMotion::Pivot;
    const WalkResult w = walk_path(m, straight_path(1e6), steady);
    const WalkResult p = walk_path(m, straight_path(1e6), pivot);
    const RootMotionReport rw = measure_root_motion(w.motion, w.labels), rp = measure_root_motion(p.motion, p.labels);
    std::printf("[walkcycle] %-13s 10 steps: root speed %.2f-%.2f m/s (mean %.2f), peak acceleration %.1f m/s^2 | pivoting root "
                "%.2f-%.2f m/s, %.1f m/s^2 | feet roll up to %.1f deg, pelvis drops up to %.1f mm\n",
                name.c_str(), rw.speed_min_mps, rw.speed_max_mps, rw.speed_mean_mps, rw.accel_max_mps2, rp.speed_min_mps,
                rp.speed_max_mps, rp.accel_max_mps2, rad2deg(w.foot_roll_max), 1e3 * w.pelvis_drop_max);
    EXPECT_GT(rw.speed_min_mps, 0.8 * rw.speed_mean_mps) << name;
    EXPECT_LT(rw.speed_max_mps, 1.2 * rw.speed_mean_mps) << name;
    EXPECT_LE(rw.accel_max_mps2, 10.0) << name;
    EXPECT_GT(rp.accel_max_mps2, 10.0) << name;  // (the measure sees the lunges)
    EXPECT_LT(rp.speed_min_mps, 0.8 * rp.speed_mean_mps) << name;
    // Both walk the same steps to the same place.
    EXPECT_EQ(w.steps, p.steps) << name;
    EXPECT_NEAR(w.end_position.z(), p.end_position.z(), 1e-6) << name;
    EXPECT_LE(measure_stance_slip(m, w.motion, w.labels).max_mm, 1.0) << name;
    // The footprints are the pivoting walk's (the feet go where it put them).
    ASSERT_EQ(w.footsteps.size(), p.footsteps.size()) << name;
    for (std::size_t i = 0; i < w.footsteps.size(); ++i) EXPECT_LT((w.footsteps[i].heel - p.footsteps[i].heel).norm(), 1e-9) << name;
    // No knee straightens past its length (hip to ankle), on every frame.
    EXPECT_LE(w.leg_reach_max, 1.0 + 1e-9) << name;
    EXPECT_EQ(w.reach_limited_frames, 0) << name;
    for (int f = 0; f < w.motion.frame_count(); ++f) {
      const auto pos = joint_positions(m.skeleton, w.motion.frame(f));
      for (Role hip : {Role::LeftHip, Role::RightHip}) {
        const auto at = [&](Role r) { return pos[static_cast<std::size_t>(m.skeleton.roles[r])]; };
        const Role knee = hip == Role::LeftHip ? Role::LeftKnee : Role::RightKnee;
        const Role ankle = hip == Role::LeftHip ? Role::LeftAnkle : Role::RightAnkle;
        EXPECT_LE((at(ankle) - at(hip)).norm(), (at(knee) - at(hip)).norm() + (at(ankle) - at(knee)).norm() + 1e-9) << name;
      }
    }
  }
}

TEST(RootMotion, SmoothRootOnTurnsAndEveryShippedPath) {
  for (const auto& name : kWalks) {
    const CycleModel m = shipped(name);
    for (const char* file : {"quarter-turn", "s-curve"}) {
      const Path path = read_path((testdata::source_dir() / "data/walks/paths" / (std::string(file) + ".json")).string());
      const WalkResult w = walk_path(m, path);
      const RootMotionReport r = measure_root_motion(w.motion, w.labels);
      EXPECT_LE(measure_stance_slip(m, w.motion, w.labels).max_mm, 2.0) << name << " " << file;
      EXPECT_LE(r.accel_max_mps2, 10.0) << name << " " << file;
      EXPECT_LT(w.end_distance, 0.05) << name << " " << file;
    }
  }
  WalkOptions bad;
  bad.soft_reach = 1.5;
  EXPECT_EQ(expect_error([&] { walk_path(shipped("normal"), straight_path(3), bad); }),
            "walk: soft_reach 1.500000 is out of range (0.5, 1]: the fraction of a leg's length it may straighten to");
}
