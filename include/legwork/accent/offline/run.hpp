#pragma once
// Offline: accentuation over a whole clip (evaluation, the CLI). Allocates.
#include <legwork/accent/accent.hpp>

#include <span>
#include <string>
#include <vector>

namespace legwork::accent {

struct AccentRun {
  Motion output;               // one frame per input frame, on the model's skeleton
  std::vector<Info> info;      // per frame
  std::vector<UpdateStatus> status;  // per frame
  double seconds = 0;          // time spent in update() only
  std::vector<float> frame_seconds;  // per frame: time in update()
  // Results that are almost certainly not what was wanted, each a sentence
  // (e.g. every frame unmatched: the body was only the direct mapping).
  std::vector<std::string> warnings;
};

// Runs one avatar of `model` over the frames (output labelled at `fps`). A
// rejected frame repeats the previous output pose. Warns when no frame
// matched the database (a user height or exaggeration far from the user, or
// a motion the database does not hold).
AccentRun accentuate(const Model& model, std::span<const TrackerFrame> frames, double fps);
// Convenience: input = a motion's head and hands, resampled to the database
// rate; settings.user_height (if 0) = the motion's standing height. Throws
// legwork::Error if the motion has no head or hand joints.
AccentRun accentuate_motion(const Database& db, Settings settings, const Motion& input);

// The tracked devices as a 3-joint figure (Head root at the head position,
// LeftHand/RightHand offsets from it) at `fps`, one frame per input frame;
// unusable samples show the last good position (as the runtime holds them).
// For pictures and videos of the input.
Motion input_markers(std::span<const TrackerFrame> frames, double fps);

}  // namespace legwork::accent
