#pragma once
// Building the learned walking-in-place depth mapping (legwork/wip/learned.hpp)
// from real walking, and its text file. Offline: allocates, throws
// legwork::Error.
//
// Training frames come from running the method (any mapping: the cycle
// coordinates, the lead foot and the apex estimates in wip::Info do not depend
// on it) over a walk's own ankles, paired with the walk's true fore-aft ankle
// offsets from the pelvis at the same frames (legwork::eval::true_depths).
#include <legwork/wip/learned.hpp>
#include <legwork/wip/wip.hpp>

#include <span>
#include <string>
#include <vector>

namespace legwork::wip {

struct LearnSample {
  double own = 0, other = 0;  // cycle coordinates of this foot and the other one
  int lead = 0;               // 1: this foot landed last
  double since = 0;           // s since the last foot strike
  double apex = 0;            // mean of both feet's apex estimates, m
  double cadence = 0;         // strides per second (1 / Info::stride_period)
  double z = 0;               // true depth / leg length
  double amplitude = 0;       // the walk's depth amplitude / leg length (half its 5-95 % range while walking)
  double turn = 0;            // smoothed head-yaw speed, rad/s (Info::turn_rate)
};

// Training samples of one run: both feet of every frame while walking, from
// `settle` seconds on, with a known lead foot and finite true depths
// (true_z[f][i] belongs to frames[i]); all carry the run's depth amplitude.
std::vector<LearnSample> learning_samples(std::span<const Info> frames, std::span<const double> true_left,
                                          std::span<const double> true_right, double leg_length, double settle = 0.5);

// The shape table (trilinear splatting of z / amplitude onto the grid nodes,
// empty nodes from the nearest filled one) and the amplitude's plane over
// apex and cadence (least squares, clamped to the training amplitudes).
// Throws if there are fewer than `min_samples` samples.
LearnedMapping build_learned_mapping(std::span<const LearnSample> samples, int min_samples = 200);

// Text file: "legwork-wip-learned-mapping 1", key/value lines (nodes,
// amplitude_intercept, amplitude_slope, cadence_slope, amplitude_min,
// amplitude_max, apex_mean, cadence_mean, samples, source), then "lead 0"
// and "lead 1" each followed by, for each since node, "since k" and kNodes
// rows of kNodes numbers (the shape, rows = own cycle coordinate 0..2, columns = the other foot's).
std::string format_learned_mapping(const LearnedMapping& m, const std::string& source);
// Parses that text; errors name `path`, the line and the field.
LearnedMapping parse_learned_mapping(const std::string& text, const std::string& path);
void write_learned_mapping(const std::string& path, const LearnedMapping& m, const std::string& source);
LearnedMapping read_learned_mapping(const std::string& path);

}  // namespace legwork::wip
