// Walking-in-place evaluation: step scoring against true and synthetic
// swings, depth agreement with the real feet, and the key-frame baseline.
#include <legwork/eval/wip.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/wip/offline/run.hpp>
#include <legwork/wip/offline/walk_cycle.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <filesystem>

namespace legwork::eval {
namespace {

Motion load(const std::string& rel) { return testdata::load_sample(rel); }

TEST(WipScore, OverlappingSwingsMatchOneToOneAndLatenciesAreSigned) {
  const std::vector<SwingEvent> truth = {{kLeft, 1.0, 1.5, 0.1}, {kRight, 2.0, 2.5, 0.1}, {kLeft, 3.0, 3.5, 0.1}};
  // A late left detection, a right one on the wrong foot's time, and a spurious left one.
  const std::vector<SwingEvent> det = {{kLeft, 1.1, 1.55, 0.1}, {kLeft, 2.0, 2.4, 0.1}, {kLeft, 3.05, 3.45, 0.1}};
  const StepScore s = score_steps(det, truth, 0, 10);
  EXPECT_EQ(s.true_steps, 3);
  EXPECT_EQ(s.matched, 2);
  EXPECT_EQ(s.detected, 3);
  EXPECT_NEAR(s.precision, 2.0 / 3, 1e-12);
  EXPECT_NEAR(s.recall, 2.0 / 3, 1e-12);
  EXPECT_NEAR(s.off_latency_ms, (100.0 + 50.0) / 2, 1e-9);
  EXPECT_NEAR(s.strike_latency_ms, (50.0 - 50.0) / 2, 1e-9);
  // Outside [t_begin, t_end] nothing counts.
  EXPECT_EQ(score_steps(det, truth, 2.9, 10).true_steps, 1);
}

TEST(Synthetic, StepsAreDetectedAtSeveralRatesWithNoiseAndDrops) {
  for (double rate : {30.0, 60.0, 90.0, 120.0}) {
    wip::SyntheticOptions o;
    o.rate = rate;
    o.asymmetry = 0.3;
    const auto track = wip::synthetic_stepping(o);
    wip::Settings p;
    p.signal.rate = rate;
    const auto run = wip::run_wip(wip::make_model(testdata::sample_skeleton(), p), track.frames, {true, 3.0, false});
    const auto score = score_steps(detected_swings(run.frames), track.swings, 0, o.duration);
    EXPECT_GE(score.f1, 0.95) << rate << " Hz: " << score.matched << "/" << score.true_steps << " matched, "
                              << score.detected << " detected";
  }
}

// ---- real walking ----------------------------------------------------------

const std::vector<std::string> kSampleTrials = {"05_01", "07_01", "07_02", "07_12", "10_04", "16_15", "16_21"};

TEST(RealWalking, StepsAreDetectedAndDepthsFollowTheRealFeetOnSampleTrials) {
  const Motion cycle = wip::extract_walk_cycle(load("cmu/bvh/walking/07_01.bvh"));
  std::vector<StepScore> scores;
  Agreement depth, baseline;
  int i = 0;
  for (const auto& name : kSampleTrials) {
    const auto e = evaluate_wip_trial(load("cmu/bvh/walking/" + name + ".bvh"), name, cycle, {}, i++);
    scores.push_back(e.steps);
    depth.merge(e.depth);
    baseline.merge(e.baseline_depth);
  }
  depth.finish();
  baseline.finish();
  const auto all = combine(scores);
  EXPECT_GE(all.true_steps, 20);
  EXPECT_GE(all.f1, 0.85) << all.matched << "/" << all.true_steps;
  EXPECT_GT(all.off_latency_ms, 0);    // causal filtering: detection follows the event
  EXPECT_LT(all.off_latency_ms, 250);
  EXPECT_GT(depth.correlation, 0.8);
  EXPECT_LT(depth.rms, 0.15);
  EXPECT_GT(depth.correlation, baseline.correlation + 0.2);  // synchronised legs beat the canned clip
}

TEST(RealWalking, FullSharedSetKeepsStepF1Above90Percent) {
  LEGWORK_REQUIRE_SHARED_CMU();
  const Motion cycle = wip::extract_walk_cycle(load("cmu/bvh/walking/07_01.bvh"));
  std::vector<StepScore> clean, noisy;
  int i = 0;
  for (const auto& entry : std::filesystem::directory_iterator(testdata::shared_cmu() / "bvh" / "walking")) {
    if (entry.path().extension() != ".bvh") continue;
    io::BvhReadOptions opt;
    opt.drop_first_frame = true;
    const auto e = evaluate_wip_trial(io::load_bvh(entry.path().string(), opt), entry.path().stem().string(), cycle, {}, i++);
    clean.push_back(e.steps);
    noisy.push_back(e.steps_noisy);
  }
  EXPECT_GE(i, 50);
  EXPECT_GE(combine(clean).f1, 0.9);
  EXPECT_GE(combine(noisy).f1, 0.85);
}

}  // namespace
}  // namespace legwork::eval
