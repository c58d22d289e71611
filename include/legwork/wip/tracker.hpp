#pragma once
// Tracker input for walking-in-place: one sample per frame with a timestamp
// and the world positions of both ankles (metres, legwork world frame, y up).
// Sources: a tracker CSV table, a BVH motion whose ankle joints act as the
// tracker (real mocap), and a synthetic in-place stepping generator.
// Offline code: may allocate and throw legwork::Error.
#include <legwork/core/motion.hpp>
#include <legwork/io/tracker_csv.hpp>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace legwork::wip {

enum Foot : int { kLeft = 0, kRight = 1 };

struct TrackerSample {
  double time = 0;                        // seconds, strictly increasing
  Vec3 ankle[2] = {Vec3::Zero(), Vec3::Zero()};  // world, metres; [kLeft], [kRight]
  bool valid[2] = {true, true};           // false = dropped sample (position ignored)
};

// From a tracker CSV table: points named left_ankle/right_ankle (also
// accepted: left_foot/right_foot, ankle_l/ankle_r, l_ankle/r_ankle). Throws
// legwork::Error naming `source` and the points present if they are absent.
std::vector<TrackerSample> samples_from_table(const io::TrackerTable& table, const std::string& source);
// The inverse, for writing synthetic input as CSV.
io::TrackerTable table_from_samples(const std::vector<TrackerSample>& samples);

// A motion's ankle joints (roles LeftAnkle/RightAnkle) sampled at `rate` Hz
// (the motion is resampled by interpolation). Throws if the roles are missing.
std::vector<TrackerSample> samples_from_motion(const Motion& m, double rate = 30.0);

// A true or synthetic swing of one foot: foot-off and foot-strike times.
struct SwingEvent {
  int foot = kLeft;
  double off = 0, strike = 0;  // seconds
  double apex = 0;             // peak lift, metres
};

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
};
struct SyntheticTrack {
  std::vector<TrackerSample> samples;
  std::vector<SwingEvent> swings;  // ground truth
};
SyntheticTrack synthetic_stepping(const SyntheticOptions& opt);

// Seeded Kinect-like corruption of existing samples: jitter (metres, per
// coordinate) and dropped samples.
void add_tracker_noise(std::vector<TrackerSample>& samples, double noise, double drop_rate, std::uint64_t seed);

}  // namespace legwork::wip
