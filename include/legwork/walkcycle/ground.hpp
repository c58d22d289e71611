#pragma once
// Uneven ground (issue 14, item 3), shared by walks along paths (offline:
// parsed from the path JSON's "ground", offline/ground.hpp) and the live
// walker (walker.hpp, Settings::ground): a slope, a height field or stairs;
// heights in metres above y = 0, x and z on the floor. Runtime code:
// height() allocates nothing and throws nothing.
//
//   slope:       height = grade * (distance along direction from origin, clamped to [0, length])
//   heightfield: heights[row][column] at (origin.x + column * cell, origin.z + row * cell),
//                bilinear between, the edge values beyond
//   stairs:      `count` steps up along the direction (down for a negative rise), the first riser
//                at the origin, treads `run` deep, the last tread the landing on top
#include <legwork/core/types.hpp>
#include <legwork/walkcycle/cycle.hpp>

#include <string>
#include <vector>

namespace legwork::walkcycle {

struct Ground {
  enum class Kind : unsigned char { Flat, Slope, HeightField, Stairs };
  Kind kind = Kind::Flat;
  Vec3 origin = Vec3::Zero();      // slope: where the ramp starts; height field: the grid's first point (y ignored)
  Vec3 direction = Vec3::UnitZ();  // slope, stairs: uphill for a positive grade / rise (unit, horizontal)
  double grade = 0;                // slope: rise per metre
  double length = 1e9;             // slope: metres of ramp, flat beyond
  double cell = 1;                 // height field: grid spacing, metres
  int columns = 0, rows = 0;       // height field: grid size (x, z)
  std::vector<double> heights;     // height field: row-major, rows * columns
  double rise = 0, run = 1;        // stairs: height of a step, depth of a tread, metres
  static constexpr double kMinRun = 0.2, kMaxRun = 5.0;  // stairs: tread depths a foot fits on / the walker searches
  int count = 0;                   // stairs: number of steps

  bool flat() const { return kind == Kind::Flat; }
  bool stepped() const { return kind == Kind::Stairs; }  // a height that jumps: feet planted flat on treads
  // Ground height under the floor point (x, z), metres.
  double height(double x, double z) const;
  double height(const Vec3& p) const { return height(p.x(), p.z()); }
  // "flat", "slope 10.0 % over 4.00 m", "height field 8 x 12, 0.50 m cells, 0.000-0.300 m".
  std::string describe() const;
};

// Where a foot stands on stairs over a plant: the extent of its heel, ball
// and toe tip along the stairs, and of its ball alone (metres from the
// stairs' origin, over every frame of the plant).
struct FootExtent {
  double lo = 1e300, hi = -1e300, ball_lo = 1e300, ball_hi = -1e300;
};

// Stairs (walk_path's plants and the live walker's): a foot that would stand
// across a tread's edge is moved along the stairs, the least it takes (1 cm
// steps, up to a tread's depth), until its ball stays at least 2 cm from an
// edge, its heel is not lower than the tread under the ball (it may overhang
// the tread below, as on real stairs) and its toe tip stays 2 cm short of
// the riser ahead (a foot rolled on its ball moves its toe base forward by
// up to a centimetre). Returns the move (metres along the stairs'
// direction) and the tread's height in `height`. No allocation.
double fit_on_tread(const Ground& ground, const FootExtent& e, double& height);

// The foot of a plan walked on the flat floor put on the ground: placed on
// `anchor` (the ball if `anchor_ball`, else the heel: the point it pivots
// on) raised by the ground height under it, and turned rigidly towards the
// line between its heel and ball each raised by the ground under them
// (`full`) - fully while the foot is flat, not at all once heel and ball
// differ in height by 5 cm or more (a foot on its heel or ball touches the
// ground at one point only; its toes still follow the ground). A rigid foot
// turned on a slope moves its other point sideways by the turn times their
// height difference, which is what makes the switch from heel to ball slip;
// fading the turn out keeps that near a millimetre on a 12 % grade. Flat
// ground and stairs (planted flat on the treads by walk_path and the live walker) leave the foot
// alone. Returns the turn applied.
Quat fit_to_ground(const Ground& ground, const FootPivots& foot, bool anchor_ball, Transform& ankle, Quat& full);

}  // namespace legwork::walkcycle
