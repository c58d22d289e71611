#pragma once
// Foot contacts and gait events from motion capture: the one detector every
// module uses (walking-in-place ground truth and evaluation, walk-cycle
// extraction, the key-frame baseline's cycle, footprints in pictures).
// Analysis of whole clips: allocates, throws legwork::Error.
#include <legwork/core/motion.hpp>

#include <array>
#include <vector>

namespace legwork {

// Contact of each foot from its ankle (heel) and toe heights.
//
// Learned (default): each joint's floor follows a drifting capture floor (the
// median height of its resting frames within +-floor_window), its stance
// height is a low percentile of its height above that floor and its lift
// range the distance from there to a high percentile, so a subject whose
// ankle rests 3-5 cm above the lowest sample is judged against its own
// stance level, not a fixed margin. A foot leaves contact when both its
// joints rise above stance + max(lift_off x range, min_lift_off) and comes
// back when one joint is below stance + max(lift_on x range, min_lift_on) and
// slower than `speed_tol` (hysteresis: lift_on < lift_off).
//
// Fixed margin (learned = false, the former detector): a foot is down when
// its ankle or toe is within `height_tol` of its local floor (rolling minimum
// over +-floor_window) and slower than `speed_tol`.
//
// Foot-off = the foot leaves contact, foot-strike = the first contact again.
struct ContactOptions {
  bool learned = true;
  double stance_percentile = 0.05;  // stance height of a joint: this quantile of its height
  double lift_percentile = 0.95;    // lift range: this quantile minus the stance height
  double lift_off = 0.25;           // fraction of the lift range to leave contact
  double lift_on = 0.15;            // fraction of the lift range to come back (hysteresis)
  double min_lift_off = 0.02;       // m: never leave contact below this lift (still subjects)
  double min_lift_on = 0.012;       // m
  double height_tol = 0.03;         // m, fixed-margin detector
  double floor_window = 1.0;        // s each side
  double speed_tol = 0.5;           // m/s
  double min_swing = 0.15;          // s: shorter lifts are not steps
  double min_stance = 0.05;         // s: shorter touch-downs do not split a swing
  // foot_swings: also the last swing of a foot that the clip's end cuts (its
  // foot-off is seen, its strike is not; at least 50 ms long: min_swing is for
  // lifts that came back down, this one is still under way), with strike
  // = the clip's end and `cut` set. Scoring foot-offs needs it: the step was
  // taken. Off by default (gait cycles need the true strike).
  bool end_swings = false;
};

// One swing of one foot (0 = left, 1 = right): foot-off and foot-strike.
struct SwingEvent {
  int foot = 0;
  double off = 0, strike = 0;  // seconds
  double apex = 0;             // peak lift, metres
  bool cut = false;            // the clip ended mid-swing (ContactOptions::end_swings): strike = the clip's end
};

// Per frame of `m`: 1 while the foot ([0] left, [1] right) is in contact.
// Needs the ankle roles (toes optional); throws naming them otherwise.
std::array<std::vector<char>, 2> foot_contacts(const Motion& m, const ContactOptions& opt = {});
// Complete swings (not cut by the clip's ends, at least min_swing long), by
// foot-off time; with opt.end_swings also the swings the clip's end cuts.
std::vector<SwingEvent> foot_swings(const Motion& m, const ContactOptions& opt = {});
// Frames where `foot` (0 left, 1 right) strikes the floor: the first contact
// frame after a swing of at least min_swing, or after one under way at frame 0.
std::vector<int> foot_strikes(const Motion& m, int foot, const ContactOptions& opt = {});

}  // namespace legwork
