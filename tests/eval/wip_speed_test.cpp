// Walking speed of walking in place against the capture's real speed.
#include <legwork/eval/wip.hpp>
#include <legwork/eval/wip_speed.hpp>
#include <legwork/wip/offline/walk_cycle.hpp>

#include "cmu_sample.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace legwork::eval {
namespace {

// A straight line at 1 m/s with a 5 cm sideways sway at 2 Hz: the averaged
// path is the travel, the sway is not.
TEST(WalkingSpeed, TravelIsThePathOfTheAveragedPositionNotTheSway) {
  const double rate = 30;
  std::vector<Vec3> p;
  for (int i = 0; i <= 300; ++i) {
    const double t = i / rate;
    p.emplace_back(0.05 * std::sin(2 * kPi * 2 * t), 0.9, t);
  }
  EXPECT_NEAR(travelled_distance(p, rate, 1.0, 9.0), 8.0, 0.02);
  EXPECT_GT(travelled_distance(p, rate, 1.0, 9.0, 0.0), 8.5) << "without averaging the sway adds path";
  EXPECT_EQ(travelled_distance({}, rate, 0, 1), 0.0);
}

// Speed is linear in the gain: the calibrated gain scales the generated
// distance onto the real one; each held-out subject gets the gain of the others.
TEST(WalkingSpeed, CalibratedGainMatchesTheRealSpeedAndFoldsHoldOutTheirSubject) {
  const std::vector<SpeedTrial> trials = {{"a_1", "a", 10, 10, 5}, {"b_1", "b", 10, 12, 4}, {"c_1", "c", 10, 8, 4}};
  const SpeedSummary s = summarize_speed(trials, 2.0);
  EXPECT_NEAR(s.real_speed, 1.0, 1e-12);
  EXPECT_NEAR(s.wip_speed, 13.0 / 30, 1e-12);
  EXPECT_NEAR(s.calibrated_gain, 2.0 * 30 / 13, 1e-12);
  ASSERT_EQ(s.folds.size(), 3u);
  EXPECT_EQ(s.folds[0].subject, "a");
  EXPECT_NEAR(s.folds[0].gain, 2.0 * 20 / 8, 1e-12) << "subject a's gain from b and c only";
  EXPECT_NEAR(s.folds[0].wip_speed, 0.5 * 20 / 8, 1e-12);
  try {
    summarize_speed(std::vector<SpeedTrial>{{"a_1", "a", 10, 10, 0}}, 2.0);
    FAIL() << "no travel accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "walking speed: the method travelled no distance on any trial (no steps detected?)");
  }
}

// On a real walk (07_01: ~1.2 m/s over the floor) the default settings (the
// adaptive detector and its calibrated gain) walk within 40 % of the real
// speed; the document's detector with the adaptive detector's gain would not
// be the same speed (the gain is the detector's).
TEST(WalkingSpeed, TheDefaultSettingsWalkAboutTheCapturesSpeedOnARealWalk) {
  const Motion m = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  const Motion cycle = wip::extract_walk_cycle(m);
  const auto e = evaluate_wip_trial(m, "07_01", cycle, {}, 0);
  ASSERT_GT(e.speed.real_speed(), 0.8);
  EXPECT_NEAR(e.speed.wip_speed() / e.speed.real_speed(), 1.0, 0.4)
      << e.speed.wip_speed() << " vs " << e.speed.real_speed() << " m/s";
  EXPECT_EQ(wip::step_speed_gain(wip::Settings{}), wip::kAdaptiveSpeedGain);
  wip::Settings doc;
  doc.gait.detector = wip::StepDetector::Document;
  EXPECT_EQ(wip::step_speed_gain(doc), wip::kDocumentSpeedGain);
  doc.mapping.speed_gain = 3;
  EXPECT_EQ(wip::step_speed_gain(doc), 3.0);
}

}  // namespace
}  // namespace legwork::eval
