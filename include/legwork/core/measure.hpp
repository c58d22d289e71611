#pragma once
// Body measurements and unit detection.
#include <legwork/core/motion.hpp>

#include <string>

namespace legwork {

struct BodyMeasures {
  double standing_height = 0;  // floor (lowest joint/end site) to head top, rest pose
  double hip_height = 0;       // floor to pelvis, rest pose
  double leg_length = 0;       // hip + knee + ankle bone lengths (mean of both legs)
  double arm_length = 0;       // shoulder + elbow + hand bones (mean of both arms)
};
// Measured on the rest pose (identity rotations); roles must be resolved for
// hip/leg/arm figures (0 where the role is missing).
BodyMeasures measure_body(const Skeleton& skel);

// Guessed file-unit-to-metre factor from a rest-pose standing height in file
// units. Returns 0 when the height fits no known unit (metres, CMU ASF units
// = 1/0.45 inch, inches, centimetres, millimetres). `why` says what was chosen.
double guess_unit_scale(double standing_height_units, std::string* why = nullptr);

constexpr double kCmuUnitMetres = (1.0 / 0.45) * 2.54 / 100.0;

}  // namespace legwork
