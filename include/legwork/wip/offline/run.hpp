#pragma once
// Whole-clip helpers around the per-frame runtime: floor calibration from a
// standing start, a run over a clip of tracker frames, the per-frame
// diagnostics as CSV. Offline: allocates, throws legwork::Error.
#include <legwork/core/motion.hpp>
#include <legwork/wip/wip.hpp>

#include <span>
#include <string>
#include <vector>

namespace legwork::wip {

// Floor calibration from standing still: averages each ankle's height over
// the first `seconds`. Refuses (ok = false, message says why) if either
// ankle's height varies by more than `max_std` metres or too few samples are usable.
struct FloorCalibration {
  bool ok = false;
  double floor[2] = {0, 0};
  double spread[2] = {0, 0};  // std of the height, m
  std::string message;
};
FloorCalibration calibrate_floor(std::span<const TrackerFrame> frames, double seconds = 3.0, double max_std = 0.03);

struct RunOptions {
  bool calibrate = true;            // calibrate the floor first (throws if not still)
  double calibration_seconds = 3.0;
  bool keep_poses = true;           // fill Run::motion (false: the legs are not solved, Info is the same)
};
struct Run {
  std::vector<Info> frames;   // one per consumed (not rejected) tracker frame
  Motion motion;              // the avatar at those frames (rate = settings.signal.rate)
  FloorCalibration calibration;
};
Run run_wip(const Model& model, std::span<const TrackerFrame> frames, const RunOptions& opt = {});

// Median frame rate of a clip (Hz) from its time steps; throws if fewer than 3 frames.
double median_rate(std::span<const TrackerFrame> frames, const std::string& source);

// The per-frame diagnostics as CSV (phases, heights, velocities, IK targets, speed).
std::string format_info_csv(std::span<const Info> frames);

}  // namespace legwork::wip
