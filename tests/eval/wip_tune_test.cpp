// The adaptive detector's parameters chosen by cross-validation by subject,
// on the repository's sample walks (four CMU subjects).
#include <legwork/eval/wip_tune.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/wip/offline/run.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

namespace legwork::eval {
namespace {

const std::vector<DetectionTrial>& sample_trials() {
  static const std::vector<DetectionTrial> trials = [] {
    std::vector<DetectionTrial> out;
    int i = 0;
    for (const char* name : {"05_01", "07_01", "07_02", "07_12", "10_04", "16_15", "16_21"})
      out.push_back(prepare_detection_trial(testdata::load_sample(std::string("cmu/bvh/walking/") + name + ".bvh"), name,
                                            WipEvalOptions{}, i++));
    return out;
  }();
  return trials;
}

// A grid of the shipped defaults and a setting whose detection signal lags
// by far (0.5 Hz low-pass): every fold must choose the defaults, and the
// held-out figures must be exactly that point's figures on the held-out
// subject's trials, pooled.
TEST(DetectorTuning, EachSubjectIsScoredWithTheSetChosenOnTheOthers) {
  const auto& trials = sample_trials();
  DetectorParams good, never;
  never.detect_cutoff = 0.5;
  const wip::Settings settings;
  const DetectorTuning t = tune_detector(trials, settings, {never, good});
  ASSERT_EQ(t.folds.size(), 4u);  // subjects 05, 07, 10, 16
  std::set<std::string> subjects;
  int scored = 0;
  for (const auto& f : t.folds) {
    subjects.insert(f.subject);
    EXPECT_EQ(f.chosen, 1) << "fold " << f.subject;
    scored += f.trials;
  }
  EXPECT_EQ(scored, static_cast<int>(trials.size()));
  EXPECT_EQ(subjects, (std::set<std::string>{"05", "07", "10", "16"}));
  EXPECT_EQ(t.chosen_all, 1);
  EXPECT_LT(t.all[0].strict.f1, t.all[1].strict.f1 - 0.2);
  wip::Settings chosen = settings;
  good.apply(chosen);
  std::vector<DetectionCounts> parts;
  for (const auto& trial : trials) parts.push_back(score_detection(trial, chosen));
  const DetectionCounts direct = pool(parts);
  EXPECT_EQ(t.cross_validated.strict.matched, direct.strict.matched);
  EXPECT_EQ(t.cross_validated.strict.detected, direct.strict.detected);
  EXPECT_EQ(t.cross_validated.noisy.matched, direct.noisy.matched);
  EXPECT_GE(t.cross_validated.strict.f1, 0.9) << t.cross_validated.strict.matched << "/" << t.cross_validated.strict.true_steps;
  EXPECT_NE(tuning_markdown(t).find("| **all, held out** |"), std::string::npos);
}

// On the sample walks the adaptive detector (the shipped parameters) finds
// the foot-offs sooner than the document's thresholds, at no loss of F1.
TEST(DetectorTuning, AdaptiveDetectorIsEarlierThanTheDocumentsOnTheSampleWalks) {
  wip::Settings doc, ada;
  doc.gait.detector = wip::StepDetector::Document;
  ada.gait.detector = wip::StepDetector::Adaptive;
  std::vector<DetectionCounts> d, a;
  for (const auto& trial : sample_trials()) d.push_back(score_detection(trial, doc)), a.push_back(score_detection(trial, ada));
  const DetectionCounts pd = pool(d), pa = pool(a);
  EXPECT_LT(pa.strict.median_ms, pd.strict.median_ms - 30);
  EXPECT_GE(pa.strict.f1, pd.strict.f1);
  EXPECT_GE(pa.noisy.f1, pd.noisy.f1 - 0.02);
}

TEST(DetectorTuning, NothingToTuneIsAnError) {
  try {
    tune_detector({}, wip::Settings{}, default_detector_grid());
    ADD_FAILURE() << "no trials accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "detector tuning: no trials");
  }
  try {
    tune_detector(sample_trials(), wip::Settings{}, {});
    ADD_FAILURE() << "an empty grid accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "detector tuning: empty parameter grid");
  }
}

}  // namespace
}  // namespace legwork::eval

namespace legwork::eval {
namespace {

// The adaptive detector's clean detections of a prepared trial.
std::vector<SwingEvent> detections(const DetectionTrial& t, const wip::Settings& s) {
  wip::RunOptions ro;
  ro.calibrate = false;
  ro.keep_poses = false;
  return detected_swings(wip::run_wip(wip::make_model(t.skeleton, s), t.clean, ro).frames);
}

// Whether the true foot-off `truth` has a detection of its foot within +-200 ms that the strict matching pairs with it.
bool found(const DetectionTrial& t, const std::vector<SwingEvent>& det, const SwingEvent& truth) {
  for (const auto& u : unmatched_detections(t.truth, det, 0.2))
    if (u.foot == truth.foot && u.off == truth.off) return false;
  return true;
}

// Subject 105's stylised walk 105_18 (turn-arounds with start and stop shuffles; 7 of the former detector's 37
// misses): the start-step thresholds after both feet rest find its first step (a 3.5 cm ankle lift, below the 5 cm
// the detector asks before it has seen a step) and the steady terminal-swing landing finds the step at ~10.2 s,
// which the former detector missed because it took the right foot, resting 5 cm up after a turn, as still in
// swing. Scored strictly on the real trial, clean and with the Kinect-like noise: more steps found, no false step
// on its still segments.
TEST(AdaptiveDetector, StartStepsAfterRestAndTheSteadyLandingFindRealShuffleSteps) {
  LEGWORK_REQUIRE_SHARED_CMU();
  io::BvhReadOptions opt;
  opt.drop_first_frame = true;
  const Motion m = io::load_bvh((testdata::shared_cmu() / "bvh" / "walking" / "105_18.bvh").string(), opt);
  const DetectionTrial t = prepare_detection_trial(m, "105_18", WipEvalOptions{}, 0);
  const wip::Settings now;
  wip::Settings no_rest = now, no_settle = now, before = now;
  no_rest.gait.rest_time = 0;
  no_settle.gait.settle_time = 0;
  before.gait.rest_time = before.gait.settle_time = 0;
  ASSERT_GT(now.gait.rest_time, 0);
  ASSERT_GT(now.gait.settle_time, 0);

  const SwingEvent* first = nullptr;
  const SwingEvent* after_turn = nullptr;
  for (const auto& s : t.truth) {
    if (s.off >= t.t_begin && (!first || s.off < first->off)) first = &s;
    if (s.foot == kRight && std::abs(s.off - 10.2) < 0.1) after_turn = &s;
  }
  ASSERT_NE(first, nullptr);
  ASSERT_NE(after_turn, nullptr);
  const auto d_now = detections(t, now);
  EXPECT_TRUE(found(t, d_now, *first)) << "first step at " << first->off << " s";
  EXPECT_FALSE(found(t, detections(t, no_rest), *first)) << "without the start-step thresholds";
  EXPECT_TRUE(found(t, d_now, *after_turn)) << "step at " << after_turn->off << " s";
  EXPECT_FALSE(found(t, detections(t, no_settle), *after_turn)) << "without the steady landing";

  const DetectionCounts a = score_detection(t, now), b = score_detection(t, before);
  EXPECT_GE(a.strict.matched, b.strict.matched + 2);
  EXPECT_GT(a.strict.f1, b.strict.f1);
  EXPECT_GE(a.noisy.f1, b.noisy.f1);
  ASSERT_GT(a.still_minutes, 0);
  EXPECT_EQ(a.false_steps, 0);
  EXPECT_EQ(a.false_steps_noisy, 0);
}

}  // namespace
}  // namespace legwork::eval

namespace legwork::eval {
namespace {

// The minimum swing time (0.1 s, chosen by `wip tune` held out by subject): with the Kinect-like noise a jitter dip
// during a low step used to land the swing one or two frames after its foot-off, and the next rise counted a second
// step (a "split swing"; 2 of the noisy run's 14 false positives, 105_18's left foot at 20.67 s and 16_28's right
// foot at 1.17 s). Each walk is prepared with the noise `wip eval` gives it (the seed follows the trial's index in
// the sorted folder). With the minimum swing: those detections are gone, no true step is lost, clean detections
// are unchanged; without it (0 = off) the split swings come back.
TEST(AdaptiveDetector, MinimumSwingTimeStopsJitterSplittingANoisyStep) {
  LEGWORK_REQUIRE_SHARED_CMU();
  const auto dir = testdata::shared_cmu() / "bvh" / "walking";
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".bvh") names.push_back(e.path().string());
  std::sort(names.begin(), names.end());
  const wip::Settings now;
  ASSERT_NEAR(now.gait.min_swing_time, 0.1, 1e-12);
  wip::Settings off = now;
  off.gait.min_swing_time = 0;
  struct Case {
    const char* trial;
    int foot;
    double at;  // s: the split swing's second foot-off without the minimum swing
  };
  for (const Case& c : {Case{"105_18", kLeft, 20.667}, Case{"16_28", kRight, 1.167}}) {
    const std::string path = (dir / (std::string(c.trial) + ".bvh")).string();
    const auto it = std::find(names.begin(), names.end(), path);
    ASSERT_NE(it, names.end()) << path;
    io::BvhReadOptions opt;
    opt.drop_first_frame = true;
    const DetectionTrial t = prepare_detection_trial(io::load_bvh(path, opt), c.trial, WipEvalOptions{},
                                                     static_cast<int>(it - names.begin()));
    auto noisy = [&](const wip::Settings& s) {
      wip::RunOptions ro;
      ro.calibrate = false;
      ro.keep_poses = false;
      return detected_swings(wip::run_wip(wip::make_model(t.skeleton, s), t.noisy, ro).frames);
    };
    auto false_near = [&](const std::vector<SwingEvent>& det) {
      int n = 0;
      for (const auto& d : unmatched_detections(det, t.truth, 0.2)) n += d.foot == c.foot && std::abs(d.off - c.at) < 0.02;
      return n;
    };
    auto shortest = [&](const std::vector<SwingEvent>& det) {
      double m = 1e9;
      for (const auto& d : det)
        if (d.strike > d.off) m = std::min(m, d.strike - d.off);
      return m;
    };
    const auto d_now = noisy(now), d_off = noisy(off);
    EXPECT_EQ(false_near(d_off), 1) << c.trial << ": the split swing without the minimum swing time";
    EXPECT_EQ(false_near(d_now), 0) << c.trial;
    EXPECT_LT(shortest(d_off), 0.07) << c.trial;
    EXPECT_GE(shortest(d_now), 0.1 - 1e-6) << c.trial << ": no detected swing shorter than the minimum";
    const DetectionCounts a = score_detection(t, now), b = score_detection(t, off);
    EXPECT_EQ(a.noisy.matched, b.noisy.matched) << c.trial;
    EXPECT_LT(a.noisy.detected, b.noisy.detected) << c.trial;
    EXPECT_GT(a.noisy.f1, b.noisy.f1) << c.trial;
    EXPECT_EQ(a.strict.matched, b.strict.matched) << c.trial;
    EXPECT_EQ(a.strict.detected, b.strict.detected) << c.trial;
  }
}

}  // namespace
}  // namespace legwork::eval
