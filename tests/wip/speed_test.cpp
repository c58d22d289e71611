// Forward-speed estimators for walking in place (src/wip/speed.cpp), fed
// gait events and foot speeds whose averages and cadences are known.
#include <legwork/wip/speed.hpp>

#include <legwork/core/tracker.hpp>

#include <gtest/gtest.h>

namespace legwork::wip {
namespace {

// Feeds `foot` vertical speeds `v` for `steps` updates of `dt` from time t,
// with `events` on the last update; returns the time after.
double feed(SpeedEstimator& e, int foot, double t, double dt, int steps, double v, unsigned events, bool walking = true) {
  for (int i = 0; i < steps; ++i) {
    t += dt;
    e.observe({t, dt, foot, i + 1 == steps ? events : 0u, i % 2 ? v : -v, walking});
  }
  return t;
}

TEST(StepSpeed, MeanVerticalFootSpeedSinceTheLastTransitionTimesTheGain) {
  StepSpeedEstimator e;
  EXPECT_EQ(e.target_speed(0), 0.0);
  double t = feed(e, kLeft, 0, 0.01, 20, 0.4, kEventFootOff);  // before the swing: not counted
  EXPECT_EQ(e.target_speed(t), 0.0);
  // Half the swing at 0.2 m/s, half at 0.6 m/s: mean 0.4 m/s.
  t = feed(e, kLeft, t, 0.01, 10, 0.2, 0);
  t = feed(e, kLeft, t, 0.01, 10, 0.6, kEventMidSwing);
  EXPECT_NEAR(e.target_speed(t), e.gain * 0.4, 1e-12);
  // The next transition averages only what came after the previous one.
  t = feed(e, kLeft, t, 0.01, 15, 0.3, kEventTerminal);
  EXPECT_NEAR(e.target_speed(t), e.gain * 0.3, 1e-12);
}

TEST(StepSpeed, FeetAverageSeparatelyAndIdleOrStopMeansZero) {
  StepSpeedEstimator e;
  double t = 0;
  for (int i = 0; i < 30; ++i) {  // interleaved, as per-foot calls per update
    t += 0.01;
    e.observe({t, 0.01, kLeft, 0, 0.5, true});
    e.observe({t, 0.01, kRight, 0, 0.1, true});
  }
  e.observe({t + 0.01, 0.01, kRight, kEventMidSwing, 0.1, true});
  EXPECT_NEAR(e.target_speed(t), e.gain * 0.1, 1e-12);  // the right foot's own mean
  e.observe({t + 0.02, 0.01, kLeft, kEventMidSwing, 0.5, true});
  EXPECT_NEAR(e.target_speed(t + 0.02), e.gain * 0.5, 1e-12);
  // No swing for longer than idle_stop: standing still.
  EXPECT_NEAR(e.target_speed(t + 0.01 + e.idle_stop), e.gain * 0.5, 1e-12);
  EXPECT_EQ(e.target_speed(t + 0.03 + e.idle_stop), 0.0);
  // The stop rule fired: zero at once.
  e.observe({t + 0.03, 0.01, kLeft, 0, 0.5, false});
  EXPECT_EQ(e.target_speed(t + 0.03), 0.0);
  e.reset();
  EXPECT_EQ(e.target_speed(0), 0.0);
}

TEST(StepFrequency, StridePerStepTimesTheCadence) {
  StepFrequencyEstimator e;
  double t = 0;
  e.observe({t, 0.01, kLeft, kEventFootOff, 0, true});
  EXPECT_EQ(e.target_speed(t), 0.0);  // one foot-off is no cadence yet
  for (int step = 0; step < 4; ++step) {
    t += 0.5;  // two steps a second
    e.observe({t, 0.01, step % 2 ? kLeft : kRight, kEventFootOff, 0, true});
    EXPECT_NEAR(e.target_speed(t), e.stride_per_step / 0.5, 1e-12);
  }
  t += 0.25;  // quicker steps: faster
  e.observe({t, 0.01, kLeft, kEventFootOff, 0, true});
  EXPECT_NEAR(e.target_speed(t), e.stride_per_step / 0.25, 1e-12);
  // A pause longer than max_interval is not a cadence: the speed stays.
  t += e.max_interval + 0.1;
  e.observe({t, 0.01, kRight, kEventFootOff, 0, true});
  EXPECT_NEAR(e.target_speed(t), e.stride_per_step / 0.25, 1e-12);
  EXPECT_EQ(e.target_speed(t + e.idle_stop + 0.01), 0.0);
  e.observe({t + 0.1, 0.01, kLeft, 0, 0, false});
  EXPECT_EQ(e.target_speed(t + 0.1), 0.0);
  e.reset();
  EXPECT_EQ(e.target_speed(0), 0.0);
}

TEST(StepSpeed, CalibratedGainMapsTheRecordedSwingSpeedToTheTarget) {
  EXPECT_DOUBLE_EQ(calibrate_step_speed_gain(0.5), 1.3 / 0.5);
  EXPECT_DOUBLE_EQ(calibrate_step_speed_gain(0.4, 1.0), 2.5);
  EXPECT_EQ(calibrate_step_speed_gain(0.0), 0.0);  // no swing recorded: no gain, not infinity
  EXPECT_EQ(calibrate_step_speed_gain(-1.0), 0.0);
  StepSpeedEstimator e;
  e.gain = calibrate_step_speed_gain(0.45, 1.2);
  const double t = feed(e, kRight, 0, 0.02, 12, 0.45, kEventMidSwing);
  EXPECT_NEAR(e.target_speed(t), 1.2, 1e-12);
}

}  // namespace
}  // namespace legwork::wip
