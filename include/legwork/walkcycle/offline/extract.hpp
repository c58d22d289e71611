#pragma once
// Key poses from motion capture (offline).
//
// extract_walk() finds each step of a real walking clip - foot strike from
// the ankle's height above a rolling floor estimate and its speed, down and
// up from the pelvis height minimum (contact..pass) and maximum (pass..next
// contact), pass where the swing ankle crosses the stance ankle along the
// step's direction - keeps the steady steps (duration within 25 % of the
// median, turning less than 25 degrees), mirrors right-foot steps into
// left-foot ones, and averages each key pose over them (heading removed, root
// height "floor"). The result is a key-pose file an animator can stylise.
// It also re-synthesises the cycle from the extracted keys and compares it
// with the clip's own mean cycle (joint positions relative to the pelvis,
// heading removed), so the loss of going down to four keys is known.
#include <legwork/walkcycle/keys.hpp>

#include <vector>

namespace legwork::walkcycle {

struct StepEvents {
  bool left = true;  // stance foot (the one striking at `contact`)
  int contact = 0, down = 0, pass = 0, up = 0, next_contact = 0;  // frames of the clip
  bool used = false;  // steady: used for the key poses
};

struct ExtractOptions {
  int frames_per_cycle = 0;  // 0: the clip's mean cycle at `fps`, rounded to even
  double fps = 24.0;
  double floor_window_s = 0.75;  // rolling floor (per ankle) half-width, seconds
};

struct Extraction {
  WalkKeys keys;
  std::vector<StepEvents> steps;  // every complete step found, in time order
  int steps_used = 0;
  double cycle_seconds = 0;        // mean of two steady steps
  double resynthesis_mean_mm = 0;  // cycle from the keys vs the clip's mean cycle
  double resynthesis_max_mm = 0;
};

// Throws legwork::Error if fewer than two steady steps are found.
Extraction extract_walk(const Motion& clip, const ExtractOptions& opt = {});

// Key poses from four frames of a clip (contact, down, pass, up, in order);
// timing from their spacing, the next contact assumed one key interval after
// up. Mirrored if the right foot is in front at contact.
WalkKeys keys_from_frames(const Motion& clip, const std::vector<int>& frames, int frames_per_cycle, double fps);

// Strike frames of one foot (exposed for tests): ankle within 25 % of its
// typical lift above its rolling minimum and slower than half its typical swing
// speed, after having been lifted above 40 % of the typical lift.
std::vector<int> foot_strikes(const Motion& clip, bool left, double floor_window_s = 0.75);

}  // namespace legwork::walkcycle
