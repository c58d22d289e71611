// Uneven ground (offline/ground.cpp, issue 14 item 3): the shipped ground
// paths parse to the heights they describe, bad grounds fail clearly, and
// every shipped walk goes up the ramp and over the hill with its feet on the
// ground (no slip, no penetration) and the pelvis following smoothly.
#include <legwork/core/fk.hpp>
#include <legwork/walkcycle/offline/measure.hpp>
#include <legwork/walkcycle/offline/path.hpp>
#include <legwork/walkcycle/offline/walk.hpp>

#include "testdata.hpp"
#include "walk_samples.hpp"

#include <cstdio>
#include <map>

using namespace legwork;
using namespace legwork::walkcycle;
using namespace legwork::walkcycle::samples;

namespace {

Path shipped_path(const std::string& name) {
  return read_path((testdata::source_dir() / "data/walks/paths" / (name + ".json")).string());
}

// Largest vertical acceleration of the root over the cruising frames, m/s^2.
double root_vertical_accel(const WalkResult& w) {
  double worst = 0;
  const double fps = w.motion.fps;
  for (int f = 2; f < w.motion.frame_count(); ++f) {
    const auto& l = w.labels[static_cast<std::size_t>(f)];
    if (l.stopping || l.step < 1) continue;
    const double y0 = w.motion.frame(f - 2).translations[0].y(), y1 = w.motion.frame(f - 1).translations[0].y(),
                 y2 = w.motion.frame(f).translations[0].y();
    worst = std::max(worst, std::abs(y2 - 2 * y1 + y0) * fps * fps);
  }
  return worst;
}

}  // namespace

TEST(Ground, ShippedGroundsHaveTheHeightsTheyDescribe) {
  const Path ramp = shipped_path("ramp");
  ASSERT_EQ(ramp.ground.kind, Ground::Kind::Slope);
  EXPECT_NEAR(ramp.ground.height(0, 0.5), 0.0, 1e-12);
  EXPECT_NEAR(ramp.ground.height(0, 3.0), 0.24, 1e-12);   // 2 m up a 12 % grade
  EXPECT_NEAR(ramp.ground.height(0, 5.5), 0.48, 1e-12);   // flat on top
  EXPECT_NEAR(ramp.ground.height(7, 3.0), 0.24, 1e-12);   // the same across
  EXPECT_EQ(ramp.ground.describe(), "slope 12.0 % over 4.00 m");
  const Path hill = shipped_path("hill");
  ASSERT_EQ(hill.ground.kind, Ground::Kind::HeightField);
  EXPECT_NEAR(hill.ground.height(0, 1.0), 0.0, 1e-12);
  EXPECT_NEAR(hill.ground.height(0, 3.0), 0.15, 1e-12);
  EXPECT_NEAR(hill.ground.height(0, 4.5), 0.30, 1e-12);   // the top
  EXPECT_NEAR(hill.ground.height(0.3, 4.25), 0.275, 1e-12);  // bilinear between rows
  EXPECT_NEAR(hill.ground.height(0, 9.0), 0.0, 1e-12);    // beyond the grid: its edge
  EXPECT_TRUE(straight_path(3).ground.flat());
}

TEST(Ground, BadGroundsAreNamed) {
  auto msg = [](const std::string& ground) {
    return expect_error([&] { parse_path_json(R"({"polyline": [[0, 0], [0, 4]], "ground": )" + ground + "}", "p.json"); });
  };
  EXPECT_EQ(msg(R"({"slope": {"origin": [0, 0], "direction": [0, 1], "grade": 0.5}})"),
            "p.json: ground: slope: grade 0.500000: steeper than the walks can follow (at most 0.3, a 30 % grade)");
  EXPECT_EQ(msg(R"({"slope": {"origin": [0, 0], "direction": [0, 0], "grade": 0.1}})"),
            "p.json: ground: slope: direction: must not be [0, 0]");
  EXPECT_EQ(msg(R"({"heightfield": {"origin": [0, 0], "cell": 0.5, "heights": [[0, 0], [0, 0, 0]]}})"),
            "p.json: ground: heightfield: heights: row 1: 3 heights, row 0 has 2");
  EXPECT_EQ(msg(R"({"heightfield": {"origin": [0, 0], "cell": 0.5, "heights": [[0, 0], [0, 0.2]]}})"),
            "p.json: ground: heightfield: heights: row 0, column 1: rises 0.200000 m to its neighbour over a 0.500000 m cell, "
            "steeper than the walks can follow (at most 0.3 m per metre; steps are not supported)");
  EXPECT_EQ(msg(R"({"steps": {}})"),
            "p.json: ground: expected {\"slope\": {...}}, {\"heightfield\": {...}} or {\"stairs\": {...}}");
  EXPECT_EQ(msg(R"({"stairs": {"origin": [0, 1], "direction": [0, 1], "rise": 0.3, "run": 0.3, "count": 3}})"),
            "p.json: ground: stairs: rise 0.300000: expected metres, 0 < |rise| <= 0.2 (higher steps than the legs can take)");
  EXPECT_EQ(msg(R"({"stairs": {"origin": [0, 1], "direction": [0, 1], "rise": 0.15, "run": 0.1, "count": 3}})"),
            "p.json: ground: stairs: run 0.1: expected metres, 0.2 to 5 (a tread a foot fits on; longer is a landing)");
  // Found by path_fuzz: a finite but absurd tread (1e308) overflowed the walker's tread search.
  EXPECT_EQ(msg(R"({"stairs": {"origin": [0, 1], "direction": [0, 1], "rise": 0.15, "run": 1e308, "count": 3}})"),
            "p.json: ground: stairs: run 1e+308: expected metres, 0.2 to 5 (a tread a foot fits on; longer is a landing)");
  EXPECT_EQ(msg(R"({"stairs": {"origin": [0, 1], "direction": [0, 1], "rise": 0.15, "run": 0.3, "count": 2.5}})"),
            "p.json: ground: stairs: count: expected a whole number of steps, 1 to 50");
  EXPECT_EQ(msg(R"({"stairs": {"origin": [0, 1], "direction": [0, 1], "rise": 0.15, "count": 3}})"),
            "p.json: ground: stairs: run: missing");
  EXPECT_EQ(msg(R"({"slope": {"origin": [0, 0], "direction": [0, 1], "grade": 0.1, "rise": 1}})"),
            "p.json: ground: slope: unknown field 'rise'");
  WalkOptions pivot;
  pivot.root = RootMotion::Pivot;
  EXPECT_EQ(expect_error([&] { walk_path(shipped("normal"), shipped_path("ramp"), pivot); }),
            "walk: uneven ground (slope 12.0 % over 4.00 m) needs the smooth root: the legs' IK puts the feet on it");
}

TEST(Ground, EveryShippedWalkGoesUpTheRampAndOverTheHillOnItsFeet) {
  for (const auto& name : kWalks) {
    const CycleModel m = shipped(name);
    const WalkResult flat = walk_path(m, straight_path(6.0));
    const GroundContactReport on_floor = measure_ground_contact(m, flat.motion, flat.labels, Ground{});
    const double flat_accel = root_vertical_accel(flat);
    const double stand_y = flat.motion.frame(flat.motion.frame_count() - 1).translations[0].y();
    for (const char* p : {"ramp", "hill"}) {
      const Path path = shipped_path(p);
      const WalkResult w = walk_path(m, path);
      const SlipReport slip = measure_stance_slip(m, w.motion, w.labels, w.ground);
      const GroundContactReport c = measure_ground_contact(m, w.motion, w.labels, path.ground);
      // By contact: heel and ball while each is down (a foot rising early onto its ball turns on the slope about the ball).
      const FootTurnReport feet = measure_foot_turning(m, w.motion, w.labels, path.ground);
      const Vec3 end = w.motion.frame(w.motion.frame_count() - 1).translations[0];
      const double accel = root_vertical_accel(w);
      std::printf("[walkcycle] %-13s %-4s: heel / ball slip %.2f / %.2f mm\n", name.c_str(), p, feet.heel_slip_mm, feet.ball_slip_mm);
      EXPECT_LE(feet.heel_slip_mm, 2.0) << name << " " << p;
      EXPECT_LE(feet.ball_slip_mm, 2.0) << name << " " << p;
      std::printf("[walkcycle] %-13s %-4s: slip max %.2f mm, feet below the ground %.2f mm, stance foot above it %.1f mm "
                  "(flat floor %.1f mm), root vertical acceleration %.1f m/s^2 (flat %.1f), end height above the ground "
                  "%.3f m (standing %.3f m), pelvis drop %.0f mm, end %.3f m\n",
                  name.c_str(), p, slip.max_mm, c.penetration_mm, c.stance_float_mm, on_floor.stance_float_mm, accel, flat_accel,
                  end.y() - path.ground.height(end), stand_y, w.pelvis_drop_max * 1e3, w.end_distance);
      EXPECT_LE(slip.max_mm, 2.0) << name << " " << p;
      EXPECT_LE(c.penetration_mm, 2.0) << name << " " << p;
      // The planted feet are on the ground as they were on the floor.
      EXPECT_LE(c.stance_float_mm, on_floor.stance_float_mm + 2.0) << name << " " << p;
      // The pelvis follows the ground: it stands as high above it at the end as on the floor, and
      // moves up and down no more abruptly than twice the flat walk's own bob.
      EXPECT_NEAR(end.y() - path.ground.height(end), stand_y, 0.005) << name << " " << p;
      EXPECT_LE(accel, 2.0 * flat_accel) << name << " " << p;
      EXPECT_LT(w.end_distance, 0.05) << name << " " << p;
      EXPECT_EQ(w.reach_limited_frames, 0) << name << " " << p;
    }
  }
}

// Stairs (issue 14, item 3): every foot planted flat on a tread (its ball on
// one tread, heel and toe tip not below it), carried from tread to tread
// without going into a riser, the pelvis climbing smoothly.
TEST(Ground, EveryShippedWalkClimbsTheStairsOnTheTreads) {
  const Path path = shipped_path("stairs");
  ASSERT_TRUE(path.ground.stepped());
  EXPECT_EQ(path.ground.describe(), "stairs up, 5 steps of 0.150 m rise, 0.360 m run");
  EXPECT_DOUBLE_EQ(path.ground.height(0, 1.49), 0.0);
  EXPECT_DOUBLE_EQ(path.ground.height(0, 1.5), 0.15);
  EXPECT_DOUBLE_EQ(path.ground.height(0, 3.5), 0.75);
  for (const auto& name : kWalks) {
    const CycleModel m = shipped(name);
    const WalkResult flat = walk_path(m, straight_path(6.0));
    const double flat_accel = root_vertical_accel(flat);
    const double stand_y = flat.motion.frame(flat.motion.frame_count() - 1).translations[0].y();
    const WalkResult w = walk_path(m, path);
    const SlipReport slip = measure_stance_slip(m, w.motion, w.labels, w.ground);
    const FootTurnReport feet = measure_foot_turning(m, w.motion, w.labels, w.ground);
    const GroundContactReport c = measure_ground_contact(m, w.motion, w.labels, path.ground);
    const Vec3 end = w.motion.frame(w.motion.frame_count() - 1).translations[0];
    const double accel = root_vertical_accel(w);
    // Every stance foot's ball comes down on a tread: within 5 mm of the ground under it.
    std::vector<Transform> g(static_cast<std::size_t>(m.skeleton.joint_count()));
    std::map<int, double> ball_above;  // per step: lowest the stance ball gets above the ground
    for (int f = 0; f < w.motion.frame_count(); ++f) {
      forward_kinematics(m.skeleton, w.motion.frame(f), g);
      const FrameLabel& l = w.labels[static_cast<std::size_t>(f)];
      const FootPivots& foot = m.foot(l.left_stance);
      const Vec3 b = g[static_cast<std::size_t>(foot.ankle)].apply(foot.ball_local);
      auto it = ball_above.try_emplace(l.step, 1e9).first;
      it->second = std::min(it->second, b.y() - path.ground.height(b));
    }
    double worst_ball = 0;
    for (const auto& [step, above] : ball_above) worst_ball = std::max(worst_ball, above);
    std::printf("[walkcycle] %-13s stairs: slip max %.2f mm (heel %.2f, ball %.2f), feet below the ground %.2f mm, lifted out of "
                "it %.1f mm (flat %.1f), stance ball at most %.1f mm above its tread, root vertical acceleration %.1f m/s^2 "
                "(flat %.1f), end height above the ground %.3f m (standing %.3f m), pelvis drop %.0f mm, end %.3f m\n",
                name.c_str(), slip.max_mm, feet.heel_slip_mm, feet.ball_slip_mm, c.penetration_mm, w.ground_lift_max * 1e3,
                flat.ground_lift_max * 1e3, worst_ball * 1e3, accel, flat_accel, end.y() - path.ground.height(end), stand_y,
                w.pelvis_drop_max * 1e3, w.end_distance);
    EXPECT_LE(slip.max_mm, 2.0) << name;
    EXPECT_LE(feet.heel_slip_mm, 2.0) << name;
    EXPECT_LE(feet.ball_slip_mm, 2.0) << name;
    EXPECT_LE(c.penetration_mm, 2.0) << name;
    // No foot is popped out of a riser (it would be lifted by up to a riser's height): with the walk's own
    // stride lifted no more than on the floor (the keys' own dip); with the stride fitted to the treads (the
    // cycle blended towards the standing pose, whose toes dip a little more at toe-off) less than half a riser.
    WalkOptions keep;
    keep.fit_stairs_stride = false;
    EXPECT_LE(walk_path(m, path, keep).ground_lift_max, flat.ground_lift_max + 0.002) << name;
    EXPECT_LT(w.ground_lift_max, 0.5 * path.ground.rise) << name;
    EXPECT_LE(worst_ball, 0.005) << name;
    EXPECT_NEAR(end.y() - path.ground.height(end), stand_y, 0.005) << name;
    EXPECT_LE(accel, 2.0 * flat_accel) << name;
    EXPECT_LT(w.end_distance, 0.05) << name;
    EXPECT_EQ(w.reach_limited_frames, 0) << name;
  }
}

// Stairs, the stride fitted to the treads (issue 14): with the walk's own
// stride (0.71 m for the normal walk) a step climbs two 0.36 m treads and
// the body crouches to reach; fitted, every step takes one tread, its ball
// clear of the nosing, and the pelvis drops less than one riser - up and
// down the flight, wherever it starts.
TEST(Ground, StairsStrideFitsTheTreadsUpAndDown) {
  for (const double rise : {0.15, -0.15})
    for (const double origin : {1.5, 1.62}) {
      const std::string json = R"({"polyline": [[0, 0], [0, 6]], "ground": {"stairs": {"origin": [0, )" +
                               std::to_string(origin) + R"(], "direction": [0, 1], "rise": )" + std::to_string(rise) +
                               R"(, "run": 0.36, "count": 5}}})";
      const Path path = parse_path_json(json, "stairs.json");
      for (const auto& name : kWalks) {
        const CycleModel m = shipped(name);
        WalkOptions keep;
        keep.fit_stairs_stride = false;
        const WalkResult kept = walk_path(m, path, keep), w = walk_path(m, path);
        const TreadReport tk = measure_treads(m, kept.motion, kept.labels, path.ground);
        const TreadReport t = measure_treads(m, w.motion, w.labels, path.ground);
        const FootTurnReport feet = measure_foot_turning(m, w.motion, w.labels, w.ground);
        const GroundContactReport c = measure_ground_contact(m, w.motion, w.labels, path.ground);
        const RootMotionReport rk = measure_root_motion(kept.motion, kept.labels), r = measure_root_motion(w.motion, w.labels);
        std::printf("[walkcycle] %-13s stairs %+.2f from %.2f: kept stride: %d treads a step, pelvis drop %.0f mm, vertical "
                    "%.2f m/s %.1f m/s^2; fitted (%.3f m): %d, ball %.1f mm from an edge, drop %.0f mm, vertical %.2f m/s "
                    "%.1f m/s^2, slip %.2f/%.2f mm, below %.2f mm\n",
                    name.c_str(), rise, origin, tk.treads_per_step_max, kept.pelvis_drop_max * 1e3, rk.vertical_speed_max_mps,
                    rk.vertical_accel_max_mps2, w.stairs_stride, t.treads_per_step_max, t.ball_margin_mm,
                    w.pelvis_drop_max * 1e3, r.vertical_speed_max_mps, r.vertical_accel_max_mps2, feet.heel_slip_mm,
                    feet.ball_slip_mm, c.penetration_mm);
        EXPECT_DOUBLE_EQ(w.stairs_stride, 0.36) << name;
        EXPECT_EQ(t.treads_per_step_max, 1) << name << " " << rise << " " << origin;
        EXPECT_GE(t.ball_margin_mm, 20.0 - 0.5) << name;  // (fit_on_tread keeps 2 cm; the ball's roll moves it a little)
        EXPECT_GE(t.stances, w.steps - 1) << name;
        EXPECT_LE(w.pelvis_drop_max, std::abs(rise)) << name << " " << rise << " " << origin;
        EXPECT_LE(feet.heel_slip_mm, 2.0) << name;
        EXPECT_LE(feet.ball_slip_mm, 2.0) << name;
        EXPECT_LE(c.penetration_mm, 2.0) << name;
        EXPECT_LT(w.end_distance, 0.05) << name;
        EXPECT_EQ(w.reach_limited_frames, 0) << name;
        if (rise > 0 && origin == 1.5) {  // the shipped flight: the walk's own stride climbs two treads a step, crouching
          EXPECT_GE(tk.treads_per_step_max, 2) << name;
          EXPECT_GT(kept.pelvis_drop_max, std::abs(rise)) << name;
          EXPECT_LT(r.vertical_speed_max_mps, rk.vertical_speed_max_mps) << name;
        }
      }
    }
}
