// Uneven ground (offline/ground.cpp, issue 14 item 3): the shipped ground
// paths parse to the heights they describe, bad grounds fail clearly, and
// every shipped walk goes up the ramp and over the hill with its feet on the
// ground (no slip, no penetration) and the pelvis following smoothly.
#include <legwork/walkcycle/offline/measure.hpp>
#include <legwork/walkcycle/offline/path.hpp>
#include <legwork/walkcycle/offline/walk.hpp>

#include "testdata.hpp"
#include "walk_samples.hpp"

#include <cstdio>

using namespace legwork;
using namespace legwork::walkcycle;
using namespace legwork::walkcycle::testing;

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
  EXPECT_EQ(msg(R"({"stairs": {}})"), "p.json: ground: expected {\"slope\": {...}} or {\"heightfield\": {...}}");
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
      const Vec3 end = w.motion.frame(w.motion.frame_count() - 1).translations[0];
      const double accel = root_vertical_accel(w);
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
