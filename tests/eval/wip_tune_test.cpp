// The adaptive detector's parameters chosen by cross-validation by subject,
// on the repository's sample walks (four CMU subjects).
#include <legwork/eval/wip_tune.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <gtest/gtest.h>

#include <set>

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
