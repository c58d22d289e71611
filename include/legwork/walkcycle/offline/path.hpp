#pragma once
// Floor paths for walking: polylines, cubic Bezier and Catmull-Rom control
// points (JSON) or an SVG path string, flattened to a polyline of points on
// the floor (metres, y = 0). SVG coordinates map x -> x (the character's
// left at heading 0) and y -> z (forward), so a path drawn "down the page"
// walks forward. Offline code: allocates, throws legwork::Error with the
// file/field at fault (empty path, repeated points, NaN, unknown commands).
#include <legwork/core/types.hpp>
#include <legwork/walkcycle/offline/ground.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace legwork::walkcycle {

struct Path {
  std::vector<Vec3> points;   // floor polyline (y = 0), at least 2 distinct points
  std::vector<double> cumulative;  // arc length at each point, metres
  Ground ground;                   // under the path (flat unless the path file gives "ground")

  double length() const { return cumulative.empty() ? 0.0 : cumulative.back(); }
  // Point and unit tangent at arc length s (clamped to [0, length]).
  Vec3 at(double s) const;
  Vec3 tangent(double s) const;
  // Arc length of the point nearest to p among the segments from
  // `first_segment` that start before arc length `s_limit` (forward-only
  // tracking that cannot jump to a later part of a path crossing itself).
  // `segment` receives the segment index, `distance` the horizontal distance.
  double project(const Vec3& p, int first_segment, double s_limit, int* segment, double* distance) const;
  // Total absolute heading change along the path, radians.
  double total_turning() const;
};

// Largest |x| or |z| of a path point (metres).
inline constexpr double kMaxPathCoordinate = 1e6;

// Builds a path from floor points (x, z); throws on < 2 points, repeated
// consecutive points, non-finite values or coordinates beyond kMaxPathCoordinate. `what` names the source in errors.
Path make_path(const std::vector<Vec3>& points, std::string_view what);
// Straight path of `metres` along +z from the origin.
Path straight_path(double metres);

// JSON: {"polyline": [[x, z], ...]} | {"bezier": [[x, z], ...]} (3n+1 points:
// start, control, control, end, control, control, end...) |
// {"catmull_rom": [[x, z], ...]} (passes through every point) | {"svg": "M 0 0 C ..."}.
// Optional "samples_per_segment" (default 16) for the curves, optional
// "ground" (uneven ground, see ground.hpp).
Path parse_path_json(std::string_view text, std::string_view source);
Path read_path(const std::string& file);
// SVG path data: M/m, L/l, H/h, V/v, C/c, S/s, Q/q, Z/z.
Path parse_svg_path(std::string_view d, std::string_view source, int samples_per_segment = 16);

}  // namespace legwork::walkcycle
