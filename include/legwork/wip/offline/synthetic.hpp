#pragma once
// Synthetic in-place stepping (Kinect-like ankle tracks with ground truth)
// and seeded tracker corruption, as TrackerFrames (feet only).
// Offline: allocates, throws legwork::Error.
#include <legwork/core/contacts.hpp>
#include <legwork/core/tracker.hpp>

#include <cstdint>
#include <vector>

namespace legwork::wip {

// Synthetic in-place stepping, Kinect-like. Deterministic for a given seed.
struct SyntheticOptions {
  double duration = 20.0;     // seconds (including the standing lead-in)
  double rate = 30.0;         // Hz
  double stand_time = 3.0;    // still standing at the start (floor calibration)
  double cadence = 1.8;       // steps per second (both feet together)
  double step_height = 0.15;  // ankle lift of the left foot, metres (comfortable in-place stepping)
  double asymmetry = 0.0;     // right lift = step_height * (1 - asymmetry)
  double swing_fraction = 0.75;  // part of each step period a foot is in the air
  double noise = 0.015;       // Gaussian jitter per coordinate, metres (Kinect: 1-2 cm)
  double drop_rate = 0.02;    // probability a sample is flagged invalid
  double nan_rate = 0.01;     // probability a sample's coordinates are NaN (also invalid)
  double pause_start = 11.0;  // a stop in the middle: standing still from here...
  double pause_length = 3.0;  // ...for this long (0 = no pause)
  double floor_y = 0.0;       // tracker world height of the floor
  double ankle_height = 0.08; // ankle above the floor when standing
  double stance_width = 0.2;  // distance between the ankles, metres
  std::uint64_t seed = 1;
  std::size_t max_frames = 10'000'000;  // refuse longer outputs (duration * rate)
};
struct SyntheticTrack {
  std::vector<TrackerFrame> frames;  // feet only (head and hands invalid)
  std::vector<SwingEvent> swings;    // ground truth
};
SyntheticTrack synthetic_stepping(const SyntheticOptions& opt);

// Seeded Kinect-like corruption of the feet: jitter (metres, per coordinate)
// and dropped samples (valid = false).
void add_tracker_noise(std::vector<TrackerFrame>& frames, double noise, double drop_rate, std::uint64_t seed);

}  // namespace legwork::wip
