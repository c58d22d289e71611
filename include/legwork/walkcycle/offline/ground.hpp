#pragma once
// Uneven ground for walks along paths (issue 14, item 3): a slope (a ramp
// along a direction) or a height field (a grid of heights, bilinear), given
// in the path JSON's "ground" field. Heights in metres above y = 0; x, z as
// the path's. Offline code: parsing throws legwork::Error naming the field.
//
//   "ground": {"slope": {"origin": [x, z], "direction": [dx, dz], "grade": 0.1, "length": 4}}
//     height = grade * (distance along direction from origin, clamped to [0, length])
//     (length optional: no top; grade = rise per metre, |grade| <= 0.3)
//   "ground": {"heightfield": {"origin": [x, z], "cell": 0.5, "heights": [[h, h, ...], ...]}}
//     heights[row][column] at (origin.x + column * cell, origin.z + row * cell), bilinear
//     between, the edge values beyond; neighbouring heights may differ by at most 0.3 * cell
//
//   "ground": {"stairs": {"origin": [x, z], "direction": [dx, dz], "rise": 0.15, "run": 0.36, "count": 4}}
//     `count` steps up along the direction (down for a negative rise): the first riser at the
//     origin, treads `run` deep, the last tread the landing on top; height = rise * the number
//     of risers behind the point (0 < |rise| <= 0.2 m, run >= 0.2 m, 1 to 50 steps)
//
// On a slope or height field the feet follow the ground under them (it has
// no edges). On stairs each foot is planted flat on the highest tread under
// its heel and ball and carried from tread to tread in the swing (see
// docs/walkcycle.md), and walk_path shortens the steps on the flight to one
// tread each (stair_stride, walk.hpp; WalkOptions::fit_stairs_stride).
#include <legwork/walkcycle/ground.hpp>

#include <string>
#include <string_view>
#include <vector>

namespace legwork::walkcycle {

// The "ground" object of a path file (its JSON text); `source` names it in errors.
Ground parse_ground_json(std::string_view text, std::string_view source);

}  // namespace legwork::walkcycle
