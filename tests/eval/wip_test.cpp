// Walking-in-place evaluation: step scoring against true and synthetic
// swings, depth agreement with the real feet, and the key-frame baseline.
#include <legwork/eval/wip.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/wip/offline/run.hpp>
#include <legwork/wip/offline/walk_cycle.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <cmath>
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

// ---- strict foot-off matching ---------------------------------------------

TEST(StrictScore, LateDetectionIsAMissAndAFalsePositive) {
  const std::vector<SwingEvent> truth = {{kLeft, 1.0, 1.5, 0.1}};
  const std::vector<SwingEvent> det = {{kLeft, 1.25, 1.6, 0.1}};
  const StrictScore s = match_foot_offs(det, truth, 0.2, 0, 10);
  EXPECT_EQ(s.true_steps, 1);
  EXPECT_EQ(s.detected, 1);
  EXPECT_EQ(s.matched, 0);
  EXPECT_EQ(s.precision, 0);
  EXPECT_EQ(s.recall, 0);
  EXPECT_EQ(s.f1, 0);
  EXPECT_TRUE(std::isnan(s.median_ms));
  // The lenient overlap score counts the same detection as found.
  EXPECT_EQ(score_steps(det, truth, 0, 10).matched, 1);
}

TEST(StrictScore, TwoDetectionsNearOneTruthCountOnce) {
  const std::vector<SwingEvent> truth = {{kLeft, 2.0, 2.5, 0.1}};
  const std::vector<SwingEvent> det = {{kLeft, 2.1, 2.5, 0.1}, {kLeft, 2.05, 2.4, 0.1}};
  const StrictScore s = match_foot_offs(det, truth, 0.2, 0, 10);
  EXPECT_EQ(s.matched, 1);
  EXPECT_EQ(s.detected, 2);
  EXPECT_NEAR(s.precision, 0.5, 1e-12);
  EXPECT_NEAR(s.recall, 1.0, 1e-12);
  EXPECT_NEAR(s.f1, 2.0 / 3, 1e-12);
  ASSERT_EQ(s.latencies_ms.size(), 1u);
  EXPECT_NEAR(s.latencies_ms[0], 50, 1e-9);  // the closer one
}

TEST(StrictScore, ClosestPairsFirstPerFootWithSignedLatencyAndWindow) {
  const std::vector<SwingEvent> truth = {{kLeft, 1.0, 1.3, 0.1}, {kLeft, 1.3, 1.6, 0.1}, {kRight, 3.0, 3.4, 0.1},
                                         {kLeft, 9.8, 10.2, 0.1}};
  // 1.15 lies within 200 ms of both left truths; 1.35 is closest to 1.3, so
  // 1.15 goes to 1.0. The right truth gets an early detection (negative
  // latency) and a left one at its time, which must not match across feet.
  const std::vector<SwingEvent> det = {{kLeft, 1.15, 1.4, 0.1}, {kLeft, 1.35, 1.7, 0.1}, {kRight, 2.9, 3.3, 0.1},
                                       {kLeft, 3.0, 3.3, 0.1}, {kLeft, 9.85, 10.2, 0.1}};
  const StrictScore s = match_foot_offs(det, truth, 0.2, 0, 9.5);  // the last pair lies outside the window
  EXPECT_EQ(s.true_steps, 3);
  EXPECT_EQ(s.matched, 3);
  EXPECT_EQ(s.detected, 4);  // the left detection at 3.0 is false
  ASSERT_EQ(s.latencies_ms.size(), 3u);
  EXPECT_NEAR(s.median_ms, 50, 1e-9);   // latencies -100, 50, 150
  EXPECT_NEAR(s.p90_ms, 50, 1e-9);      // index floor(0.9 * 2) = 1
  EXPECT_NEAR(s.mean_ms, 100.0 / 3, 1e-9);
  // +-100 ms: the 150 ms late one becomes a miss plus a false positive.
  const StrictScore t = match_foot_offs(det, truth, 0.1, 0, 9.5);
  EXPECT_EQ(t.matched, 2);
  EXPECT_EQ(t.detected, 4);
  const StrictScore both[2] = {s, t};
  const StrictScore c = combine(both);
  EXPECT_EQ(c.matched, 5);
  EXPECT_EQ(c.true_steps, 6);
  EXPECT_EQ(c.latencies_ms.size(), 5u);
}

TEST(StrictScore, NoStepsIsNotAZeroScore) {
  const StrictScore s = match_foot_offs({}, {}, 0.2, 0, 10);
  EXPECT_TRUE(std::isnan(s.f1));
  EXPECT_TRUE(std::isnan(s.precision));
  EXPECT_TRUE(std::isnan(s.recall));
  const std::string text = format_strict(s);
  EXPECT_NE(text.find("F1 n/a"), std::string::npos) << text;
  EXPECT_NE(text.find("median n/a"), std::string::npos) << text;
  EXPECT_EQ(text.find("0.000"), std::string::npos) << text;
}

// ---- ground-truth contacts -------------------------------------------------

// 07_12: the ankle rests 3-5 cm above its rolling floor during stance (the
// floor level drifts up over the trial), so the former fixed-margin detector
// sees no contact there and merges two steps of each foot into one swing of
// over a second; the learned stance height finds each step.
TEST(TrueContacts, LearnedStanceHeightFindsStepsWhereTheFixedMarginSeesOneLongSwing) {
  const Motion m = load("cmu/bvh/walking/07_12.bvh");
  ContactOptions fixed;
  fixed.learned = false;
  const auto old_swings = foot_swings(m, fixed), swings = foot_swings(m);
  for (int foot : {kLeft, kRight}) {
    std::vector<SwingEvent> o, n;
    for (const auto& s : old_swings)
      if (s.foot == foot) o.push_back(s);
    for (const auto& s : swings)
      if (s.foot == foot) n.push_back(s);
    ASSERT_EQ(o.size(), 1u) << "foot " << foot << ": the fixed margin should merge this foot's steps";
    EXPECT_GT(o[0].strike - o[0].off, 1.2);
    ASSERT_EQ(n.size(), 2u) << "foot " << foot;
    for (const auto& s : n) {
      EXPECT_GT(s.strike - s.off, 0.3);
      EXPECT_LT(s.strike - s.off, 0.7);
      EXPECT_GT(s.apex, 0.1);  // real steps, not weight shifts
    }
    // The stance between them lies inside the old single swing.
    EXPECT_GT(n[0].strike, o[0].off);
    EXPECT_LT(n[1].off, o[0].strike);
    EXPECT_GT(n[1].off - n[0].strike, 0.1);
  }
  // Both feet alternate: left and right foot-offs interleave.
  ASSERT_EQ(swings.size(), 4u);
  for (std::size_t i = 1; i < swings.size(); ++i) EXPECT_NE(swings[i].foot, swings[i - 1].foot);
}

TEST(TrueContacts, StillSegmentsAreWhereBothFeetRest) {
  LEGWORK_REQUIRE_SHARED_CMU();
  io::BvhReadOptions opt;
  opt.drop_first_frame = true;
  const Motion m = io::load_bvh((testdata::shared_cmu() / "bvh" / "walking" / "105_02.bvh").string(), opt);
  const auto swings = foot_swings(m);
  const auto still = still_segments(m, "105_02", {}, swings, 1.0, 0.5, m.duration() - 0.1);
  ASSERT_FALSE(still.empty());
  for (const auto& g : still) {
    EXPECT_GE(g.end - g.begin, 1.0);
    EXPECT_EQ(g.false_steps, 0) << "true foot-offs inside a true still segment";
    for (const auto& s : swings) EXPECT_FALSE(s.off < g.end && s.strike > g.begin) << g.begin << "-" << g.end;
  }
  // Counting detections: a foot-off placed inside the first segment is a false step.
  std::vector<SwingEvent> det = swings;
  det.push_back({kLeft, 0.5 * (still[0].begin + still[0].end), still[0].end, 0.05});
  EXPECT_EQ(still_segments(m, "105_02", {}, det, 1.0, 0.5, m.duration() - 0.1)[0].false_steps, 1);
}

// A swing still open when the frames end is a detection too: kept, cut at
// the last frame, so a step at a clip's end is neither a miss nor dropped.
TEST(DetectedSwings, ASwingOpenAtTheLastFrameIsKeptAndFlaggedCut) {
  std::vector<wip::Info> frames(10);
  for (int i = 0; i < 10; ++i) frames[static_cast<std::size_t>(i)].time = 0.1 * i;
  frames[2].events[kLeft] = wip::kEventFootOff;
  frames[5].events[kLeft] = wip::kEventFootStrike;
  frames[7].events[kRight] = wip::kEventFootOff;
  const auto swings = detected_swings(frames);
  ASSERT_EQ(swings.size(), 2u);
  EXPECT_FALSE(swings[0].cut);
  EXPECT_NEAR(swings[0].strike, 0.5, 1e-12);
  EXPECT_EQ(swings[1].foot, kRight);
  EXPECT_TRUE(swings[1].cut);
  EXPECT_NEAR(swings[1].off, 0.7, 1e-12);
  EXPECT_NEAR(swings[1].strike, 0.9, 1e-12);
}

// ---- real walking ----------------------------------------------------------

const std::vector<std::string> kSampleTrials = {"05_01", "07_01", "07_02", "07_12", "10_04", "16_15", "16_21"};

// The document's detector (the reference; its 4 Hz filter lags, so every
// detection follows the true foot-off).
TEST(RealWalking, StepsAreDetectedAndDepthsFollowTheRealFeetOnSampleTrials) {
  const Motion cycle = wip::extract_walk_cycle(load("cmu/bvh/walking/07_01.bvh"));
  std::vector<StepScore> scores;
  std::vector<StrictScore> strict, strict_100;
  Agreement depth, baseline;
  WipEvalOptions opt;
  opt.settings.gait.detector = wip::StepDetector::Document;
  int i = 0;
  for (const auto& name : kSampleTrials) {
    const auto e = evaluate_wip_trial(load("cmu/bvh/walking/" + name + ".bvh"), name, cycle, opt, i++);
    scores.push_back(e.steps);
    strict.push_back(e.strict);
    strict_100.push_back(e.strict_100);
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
  const auto s200 = combine(strict), s100 = combine(strict_100);
  EXPECT_EQ(s200.true_steps, s100.true_steps);
  EXPECT_LE(s100.matched, s200.matched);  // a tighter window matches no more
  EXPECT_GE(s200.f1, 0.85) << s200.matched << "/" << s200.true_steps << ", " << s200.detected << " detected";
  EXPECT_GT(s200.median_ms, 0);  // causal filtering: detection follows the event
  EXPECT_LE(s200.p90_ms, 200);
}

// The learned depth mapping, cross-validated by subject on the sample walks:
// for each subject, a table from the other subjects' walks drives that
// subject's trials; pooled, it follows the real feet better than the
// document's equations (higher r, lower RMS).
TEST(LearnedMapping, HeldOutSubjectsFollowTheRealFeetBetterThanTheEquations) {
  const Motion cycle = wip::extract_walk_cycle(load("cmu/bvh/walking/07_01.bvh"));
  std::vector<Motion> motions;
  std::vector<WipTrialEval> evals;
  int i = 0;
  for (const auto& name : kSampleTrials) {
    motions.push_back(load("cmu/bvh/walking/" + name + ".bvh"));
    evals.push_back(evaluate_wip_trial(motions.back(), name, cycle, {}, i++));
    EXPECT_EQ(evals.back().subject, name.substr(0, 2));
    EXPECT_FALSE(evals.back().learn.empty()) << name;
  }
  Agreement document, learned;
  for (std::size_t t = 0; t < evals.size(); ++t) {
    std::vector<wip::LearnSample> train;
    for (const auto& o : evals)
      if (o.subject != evals[t].subject) train.insert(train.end(), o.learn.begin(), o.learn.end());
    const auto table = wip::build_learned_mapping(train);
    evaluate_learned_depth(motions[t], table, {}, evals[t]);
    EXPECT_GT(evals[t].depth_learned.samples, 50) << evals[t].name;
    document.merge(evals[t].depth);
    learned.merge(evals[t].depth_learned);
  }
  document.finish();
  learned.finish();
  EXPECT_GT(learned.correlation, document.correlation) << "learned r " << learned.correlation;
  EXPECT_LT(learned.rms, document.rms) << "learned RMS " << learned.rms;
}

TEST(LearnedMapping, TrialsThatTurnAroundAreTurningWalks) {
  LEGWORK_REQUIRE_SHARED_CMU();
  io::BvhReadOptions opt;
  opt.drop_first_frame = true;
  // 105_02 walks out and back (a half turn); 07_01 walks straight.
  const auto turn = true_depths(io::load_bvh((testdata::shared_cmu() / "bvh" / "walking" / "105_02.bvh").string(), opt), 30);
  const auto straight = true_depths(load("cmu/bvh/walking/07_01.bvh"), 30);
  EXPECT_GT(turn.heading_range_deg, kTurningDegrees);
  EXPECT_LT(straight.heading_range_deg, kTurningDegrees);
}

// The depth error's segments from the capture: 07_01 walks straight ahead;
// 09_12 ("navigate - walk forward, backward, sideways") walks forward for its
// first 7 s and backward and sideways after, which the segments show.
TEST(DepthSegments, BackwardAndSidewaysWalkingIsFoundWhereTheCaptureDoesIt) {
  const auto straight = true_depths(load("cmu/bvh/walking/07_01.bvh"), 30);
  int forward = 0, backward = 0;
  for (std::size_t i = 0; i < straight.time.size(); ++i) {
    const auto s = depth_segment(straight, i, true);
    forward += s == DepthSegment::Straight ? 1 : 0;
    backward += s == DepthSegment::Backward ? 1 : 0;
  }
  EXPECT_EQ(backward, 0);
  EXPECT_GT(forward, static_cast<int>(0.8 * static_cast<double>(straight.time.size())));
  EXPECT_EQ(depth_segment(straight, 30, false), DepthSegment::NotWalking);
  LEGWORK_REQUIRE_SHARED_CMU();
  io::BvhReadOptions opt;
  opt.drop_first_frame = true;
  const auto nav = true_depths(io::load_bvh((testdata::shared_cmu() / "bvh" / "walking" / "09_12.bvh").string(), opt), 30);
  int early = 0, late = 0, late_frames = 0;
  for (std::size_t i = 0; i < nav.time.size(); ++i) {
    const bool back = depth_segment(nav, i, true) == DepthSegment::Backward;
    if (nav.time[i] < 7) early += back ? 1 : 0;
    else late += back ? 1 : 0, ++late_frames;
  }
  EXPECT_EQ(early, 0);
  EXPECT_GT(late, late_frames / 4) << late << " of " << late_frames << " frames after 7 s";
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
