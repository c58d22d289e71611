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
#include <legwork/core/contacts.hpp>
#include <legwork/walkcycle/keys.hpp>

#include <string>
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
  ContactOptions contacts = {.floor_window = 0.75};  // foot contacts (core/contacts.hpp): strikes, flight
  double max_flight_fraction = 0.1;  // both feet off the floor longer: not a walk (run, hop) -> warning
  bool refuse_non_walks = false;     // throw instead of warning
};

struct Extraction {
  WalkKeys keys;
  std::vector<StepEvents> steps;  // every complete step found, in time order
  int steps_used = 0;
  double cycle_seconds = 0;        // mean of two steady steps
  double resynthesis_mean_mm = 0;  // cycle from the keys vs the clip's mean cycle
  double resynthesis_max_mm = 0;
  double flight_fraction = 0;      // share of the steady steps' frames with both feet off the floor
  std::string warning;             // non-empty: the clip does not look like a walk (says why)
};

// Throws legwork::Error if fewer than two steady steps are found. If both
// feet are off the floor in more than max_flight_fraction of the steady
// steps' frames (not a walk: running, hopping), sets `warning`, or throws
// with refuse_non_walks. (On the shared CMU set with the one contact detector of
// core/contacts.hpp: 32 of 34 runs are caught, no walk is flagged - walks
// measure 0-6 %, the brisk 07_12 0 %; a warning all the same.)
Extraction extract_walk(const Motion& clip, const ExtractOptions& opt = {});

// Key poses from four frames of a clip (contact, down, pass, up, in order);
// timing from their spacing, the next contact assumed one key interval after
// up. Mirrored if the right foot is in front at contact.
WalkKeys keys_from_frames(const Motion& clip, const std::vector<int>& frames, int frames_per_cycle, double fps);

}  // namespace legwork::walkcycle
