#pragma once
// Walking speed of walking in place against the capture's real speed (issue
// 13): each trial's own ankles drive the method, and the avatar's travelled
// distance is compared with the distance its pelvis really travelled. The
// step-speed model is linear in its gain below the 3.5 m/s cap, so the gain
// that makes the method walk the real speed is the used gain times the ratio
// of real to generated distance: chosen on the other subjects' walks and
// scored on each held-out subject (cross-validated by subject), and on all
// walks (the value to ship). Offline: allocates, throws legwork::Error.
#include <legwork/wip/wip.hpp>

#include <span>
#include <string>
#include <vector>

namespace legwork::eval {

struct SpeedTrial {
  std::string trial, subject;
  double seconds = 0;        // scored time ([settle, end])
  double real_distance = 0;  // m: path of the pelvis (horizontal, averaged over +-0.5 s)
  double wip_distance = 0;   // m: the avatar's travel over the same time
  double real_speed() const { return seconds > 0 ? real_distance / seconds : 0; }
  double wip_speed() const { return seconds > 0 ? wip_distance / seconds : 0; }
};

// Path length over [t0, t1] of horizontal positions sampled at `rate` Hz from
// t = 0, each averaged over +-`window` s first (the pelvis sways sideways with
// every step; that sway is not travel).
double travelled_distance(std::span<const Vec3> positions, double rate, double t0, double t1, double window = 0.5);
// The avatar's travel over [t0, t1] (Info::distance difference).
double wip_travelled(std::span<const wip::Info> frames, double t0, double t1);

struct SpeedSummary {
  int trials = 0;
  double gain = 0;              // the step-speed gain the runs used
  double real_speed = 0;        // m/s pooled (total distance / total time)
  double wip_speed = 0;         // m/s pooled, with `gain`
  double rms_error = 0;         // m/s: RMS over trials of (generated - real) mean speed, with `gain`
  double calibrated_gain = 0;   // gain that matches the pooled real speed on all trials
  double cv_wip_speed = 0;      // m/s pooled, each subject with the gain chosen on the other subjects
  double cv_rms_error = 0;      // m/s, the same per trial
  struct Fold {
    std::string subject;
    double gain = 0, real_speed = 0, wip_speed = 0;  // held-out subject: its gain (from the others) and speeds
  };
  std::vector<Fold> folds;
};
// Throws when no trial has a positive generated distance.
SpeedSummary summarize_speed(std::span<const SpeedTrial> trials, double gain);

}  // namespace legwork::eval
