#pragma once
// Per-foot signal processing (floor, ring buffer, Butterworth low-pass,
// velocity, hold-last-value with confidence decay) and the gait-phase state
// machine of one foot. Runtime: fixed-size state, no allocation, no
// exceptions. Heights are metres above the (calibrated or tracked) floor;
// velocities m/s, positive up.
#include <legwork/wip/filter.hpp>

#include <array>
#include <string_view>

namespace legwork::wip {

struct SignalSettings {
  double rate = 30.0;           // nominal sample rate, Hz (30/60/90/120 all work)
  double cutoff = 4.0;          // low-pass cutoff, Hz
  int order = 2;                // Butterworth order
  double buffer_seconds = 1.0;  // ring buffer length (the document: 30 samples at 30 Hz)
  double confidence_tau = 0.25; // s: confidence decays as exp(-t/tau) over dropped samples
  // Rolling floor: the floor follows the ankle down at once and relaxes toward
  // it with this time constant while the foot is in double support (the
  // capture floor drifts by a few cm in real recordings). 0 = fixed floor.
  double floor_tau = 2.0;
  // The adaptive step detector's signal (GaitSettings::detector == Adaptive):
  // a second, lighter low-pass of the same ankle height (less lag at foot-off),
  // a per-foot stance baseline it is measured from, and the stance noise.
  double detect_cutoff = 10.0;  // Hz: low-pass of the detection signal
  double baseline_tau = 0.5;    // s: stance baseline = running mean of the detection height while the foot is down
  double noise_tau = 1.0;       // s: running tracker jitter (RMS of the raw height about the low-passed one, feet down)
};

// One foot's processed signal.
struct FootSignal {
  static constexpr int kCapacity = 512;  // ring buffer samples (>= buffer_seconds * rate)

  Butterworth filter;
  std::array<double, kCapacity> ring{};  // filtered heights above the floor, newest at head
  int head = -1, size = 0, capacity = 30;
  double floor = 0;        // tracker-space ankle height of this foot standing
  bool has_floor = false;  // set by calibration or the first valid sample
  double raw = 0;          // last valid raw ankle height (tracker y)
  double h = 0;            // filtered height above floor, metres
  double v = 0;            // velocity of the filtered height, m/s
  double confidence = 0;   // 1 = fresh samples, decays toward 0 over dropped ones
  double held_time = 0;    // seconds since the last valid sample
  // Detection signal (the adaptive detector): height above this foot's stance
  // baseline and its velocity, from the lighter low-pass; the tracker's
  // jitter (running RMS of the raw height about the low-passed one while the
  // foot is down).
  Butterworth detect_filter;
  double hd = 0, vd = 0;
  double baseline = 0;     // stance baseline above the floor, m
  double noise = 0;        // m

  void init(const SignalSettings& p);
  // Feeds one sample (valid=false: hold the last value). dt: seconds since the
  // previous sample. `in_support` lets the rolling floor relax.
  void push(const SignalSettings& p, double y, bool valid, double dt, bool in_support);
  // Filtered height `back` samples ago (0 = newest), clamped to the buffer.
  double recent(int back) const;
  // Highest filtered height over the buffer (about the last second).
  double recent_max() const;

 private:
  void update_detection(const SignalSettings& p, double height, double jitter, bool valid, double dt, bool in_support);
};

enum class GaitPhase : unsigned char { DoubleSupport, InitialSwing, MidSwing, TerminalSwing };
std::string_view phase_name(GaitPhase p);
inline bool in_swing(GaitPhase p) { return p != GaitPhase::DoubleSupport; }

// Thresholds: the document's H1, V1, V2 as defaults. Transitions (decided
// here, the document's diagram is lost; see docs/wip.md):
//   DoubleSupport -> InitialSwing  h > H1 and v > V1            (foot-off detected)
//   InitialSwing  -> MidSwing      v < V1                       (ascent ends near the apex)
//   MidSwing      -> TerminalSwing v < -V2 or h < H1            (descending)
//   any swing     -> DoubleSupport h < land_fraction * H1 (0.3) (foot-strike detected)
//   TerminalSwing -> DoubleSupport also when the descent stops (v > -V1) below H1
// With `adaptive`, H1/V1/V2 shrink toward fractions of the user's own step
// (running estimates of apex height and peak speeds), never above the
// document's values and never below the noise floors, so real walking's low
// start/stop steps are seen.
// Foot-off detection: the document's thresholds on the 4 Hz height (the
// reference), or the adaptive detector (issue 13 item 2): the lighter
// detection signal above a per-foot stance baseline, a foot-off when it rises
// above max(lift_fraction x the running apex estimate, noise_factor x the
// stance noise, min_lift) while rising faster than the same rule for speed;
// the rest of the machine (mid-swing, landing with hysteresis) on that signal.
enum class StepDetector { Document, Adaptive };

struct GaitSettings {
  // The adaptive detector is the default (strict F1 0.955 against 0.886, latency 8 against 100 ms on the
  // 57 shared walks, no more false steps); the document's stays selectable as the reference. The step-speed
  // gain (wip.hpp, kAdaptiveSpeedGain) and the shipped learned table are calibrated with it (docs/wip.md).
  StepDetector detector = StepDetector::Adaptive;
  double h1 = 0.10;  // m
  double v1 = 0.20;  // m/s
  double v2 = 0.60;  // m/s
  double land_fraction = 0.3;    // landing height = land_fraction * H1 (hysteresis)
  double min_stance_time = 0.07; // s in double support before a new lift counts
  double max_ascent_time = 1.0;  // s: an ascent longer than this is treated as held (mid-swing)
  double lost_confidence = 0.1;  // below this, a swinging foot is put down
  bool adaptive = true;
  double height_fraction = 0.4;    // adaptive H1 = fraction * apex estimate
  double velocity_fraction = 0.25; // adaptive V1, V2 = fraction * peak speed estimates
  double min_h1 = 0.03, min_v1 = 0.08;  // noise floors for the adaptive thresholds
  double estimate_rate = 0.3;      // EMA weight of each new step in the estimates
  // Adaptive detector (detector == Adaptive): the values `legwork wip tune` chose on all 57 shared
  // walks; held out by subject the same rule scores strict F1 0.972 / noisy 0.951 with the start steps and
  // the minimum swing below (0.972 / 0.949 without the minimum swing, 0.955 / 0.950 without both; docs/wip.md).
  double lift_fraction = 0.2;      // foot-off height >= fraction * apex estimate
  double rise_fraction = 0.2;      // foot-off speed >= fraction * peak rise estimate
  double noise_factor = 2.5;       // foot-off height >= factor * tracker jitter
  double rise_noise_factor = 20.0; // foot-off speed >= this (per second) * tracker jitter
  double min_lift = 0.01;          // m: lowest foot-off height above the stance baseline
  double min_rise = 0.05;          // m/s: lowest foot-off speed
  // Start steps (adaptive detector; issue 13, chosen by `wip tune` held out by subject, docs/wip.md): once both feet have been down for rest_time s (standing, a pause, the
  // start of a session), a foot-off needs only rest_lift above the stance baseline rising at rest_rise (never
  // more than the walking thresholds above, never less than the jitter floors): start, stop and turn shuffles
  // lift the ankle 2-4 cm, below 20 % of a walking step's apex. 0 = off.
  double rest_time = 0.5;          // s
  double rest_lift = 0.02;         // m
  double rest_rise = 0.1;          // m/s
  double rest_noise_factor = 3.5;  // start steps: foot-off height >= this x tracker jitter
  // A foot in terminal swing whose detection height stops changing (|v| < V1) for this long has landed
  // above its old stance level (it rests on its toes, or the floor changed): foot-strike. 0 = off.
  double settle_time = 0.3;        // s
  // A swing cannot land (adaptive detector) before this long after its foot-off: a jitter dip during a low step
  // used to land it after one or two frames, and the next rise counted a second step (split swings). 0 = off.
  double min_swing_time = 0.1;     // s (chosen by `wip tune` held out by subject, docs/wip.md)
};

// What happened on one update.
enum GaitEvent : unsigned {
  kEventNone = 0,
  kEventFootOff = 1u << 0,    // DoubleSupport -> InitialSwing
  kEventMidSwing = 1u << 1,   // InitialSwing -> MidSwing
  kEventTerminal = 1u << 2,   // -> TerminalSwing
  kEventFootStrike = 1u << 3, // swing -> DoubleSupport
  kEventLost = 1u << 4,       // put down because tracking was lost
};

struct GaitMachine {
  GaitPhase phase = GaitPhase::DoubleSupport;
  double time_in_phase = 0;   // s
  double apex = 0;            // highest h of the current/last swing
  double peak_up = 0, peak_down = 0;  // fastest rise/fall (m/s, positive) this swing
  // Running estimates of the user's step (seeded so that the adaptive
  // thresholds start at the document's values).
  double apex_estimate = 0, up_estimate = 0, down_estimate = 0;
  int swings = 0;
  double noise = 0;                 // tracker jitter of this foot (adaptive detector), m
  double rest = 0;                  // s both feet have been down before this frame (adaptive detector)
  double steady = 0;                // s the detection height has been steady in terminal swing
  double swing_time = 0;            // s since this foot's foot-off (in swing)

  void init(const GaitSettings& p);
  double h1(const GaitSettings& p) const;
  double v1(const GaitSettings& p) const;
  double v2(const GaitSettings& p) const;
  // The adaptive detector's start thresholds apply (rest_time > 0, this foot down, both feet down that long).
  bool at_rest(const GaitSettings& p) const;
  // One step of the machine; returns the events that fired. h, v: the
  // detector's signal (FootSignal h, v for the document's detector; hd, vd
  // with `noise` set for the adaptive one).
  unsigned update(const GaitSettings& p, double h, double v, double confidence, double dt);
};

}  // namespace legwork::wip
