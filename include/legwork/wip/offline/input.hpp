#pragma once
// Tracker input for walking in place from the three sources: a tracker CSV
// (feet = the left/right ankle or foot points), a motion whose ankle joints
// act as the trackers (real mocap, with its true gait events), and synthetic
// in-place stepping. Offline: allocates, throws legwork::Error naming the source.
#include <legwork/core/motion.hpp>
#include <legwork/wip/offline/synthetic.hpp>

#include <string>
#include <vector>

namespace legwork::wip {

struct TrackerInput {
  std::vector<TrackerFrame> frames;
  double rate = 30;               // Hz (the CSV's median rate, or the sampling rate)
  std::string what;               // one line describing the source
  bool still_start = true;        // may be calibrated from a standing start
  std::vector<SwingEvent> truth;  // true swings when known (motion, synthetic)
};

// io::frames_from_table(table, path, {LeftFoot, RightFoot}); rate = the median time step's.
TrackerInput tracker_input_from_csv(const std::string& path);
// The motion's ankles sampled at `rate` Hz (tracker_frames_from_motion), with
// its true swings; throws if the motion has no ankle joints.
TrackerInput tracker_input_from_motion(const Motion& m, const std::string& name, double rate);
TrackerInput tracker_input_synthetic(const SyntheticOptions& opt);

}  // namespace legwork::wip
