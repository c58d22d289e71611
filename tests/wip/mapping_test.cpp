// Equations 1-8, avatar scaling, continuity, IK in the loop, allocation-free
// updates, speed, bad input, and behaviour on real CMU walking.
#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/wip/eval.hpp>

#include "alloc_counter.hpp"
#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>


namespace legwork::wip {
namespace {

Motion load(const std::string& rel) { return testdata::load_sample(rel); }

const WipModel& cmu_model() {
  static const WipModel m = make_wip_model(load("cmu/bvh/walking/07_01.bvh").skeleton);
  return m;
}

TEST(Equations, TakeTheRestoredValuesAtZeroAndMaximumHeight) {
  const StepShape k{0.6, 0.3};
  const double S = k.S, H = k.H;
  EXPECT_NEAR(first_step_swing(k, 0, true), 0, 1e-12);
  EXPECT_NEAR(first_step_swing(k, H, true), 0.25 * S, 1e-12);
  EXPECT_NEAR(first_step_swing(k, H, false), 0.25 * S, 1e-12);
  EXPECT_NEAR(first_step_swing(k, 0, false), 0.5 * S, 1e-12);
  EXPECT_NEAR(first_step_support(k, 0, true), 0, 1e-12);
  EXPECT_NEAR(first_step_support(k, H, true), -0.25 * S, 1e-12);
  EXPECT_NEAR(first_step_support(k, 0, false), -0.5 * S, 1e-12);
  EXPECT_NEAR(next_step_swing(k, 0, true), -0.5 * S, 1e-12);
  EXPECT_NEAR(next_step_swing(k, H, true), 0, 1e-12);
  EXPECT_NEAR(next_step_swing(k, H, false), 0, 1e-12);
  EXPECT_NEAR(next_step_swing(k, 0, false), 0.5 * S, 1e-12);
  EXPECT_NEAR(next_step_swing(k, H / 2, false), 0.5 * S * std::cos(kPi / 4) + 0.25 * S, 1e-12);  // overshoot term
  EXPECT_NEAR(next_step_support(k, 0, true), 0.5 * S, 1e-12);
  EXPECT_NEAR(next_step_support(k, H, true), 0, 1e-12);
  EXPECT_NEAR(next_step_support(k, 0, false), -0.5 * S, 1e-12);
  // Heights above H are clamped (real marching lifts 0.39 m).
  EXPECT_NEAR(next_step_swing(k, 0.5, true), next_step_swing(k, H, true), 1e-12);
  EXPECT_NEAR(body_drop(0.8, 0.0), 0.0, 1e-12);
  EXPECT_NEAR(body_drop(0.8, -0.3), 0.8 - std::sqrt(0.64 - 0.09), 1e-12);
}

TEST(Mapping, StepLengthAndHintScaleWithTheMeasuredLeg) {
  Skeleton big = cmu_model().skeleton;
  big.scale(1.25);
  const WipModel m = make_wip_model(big);
  EXPECT_NEAR(m.leg_length, 1.25 * cmu_model().leg_length, 1e-9);
  EXPECT_NEAR(m.shape.S / cmu_model().shape.S, 1.25, 1e-9);
  EXPECT_GT(cmu_model().leg_length, 0.7);
  EXPECT_LT(cmu_model().leg_length, 0.95);
}

TEST(Mapping, SkeletonWithoutLegsIsRefusedClearly) {
  Skeleton s;
  s.add_joint("Hips", -1, Vec3::Zero());
  s.add_joint("Spine", 0, Vec3(0, 0.2, 0));
  resolve_roles(s);
  try {
    make_wip_model(s);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(std::string(role_name(Role::LeftKnee))), std::string::npos) << e.what();
  }
}

TEST(Mapping, CurvesAreContinuousAndFeetFollowTheTargets) {
  SyntheticOptions o;
  o.noise = 0;
  o.drop_rate = o.nan_rate = 0;
  const auto track = synthetic_stepping(o);
  const WipModel& m = cmu_model();
  WipWorkspace ws = make_workspace(m);
  const auto cal = calibrate_floor(track.samples);
  ASSERT_TRUE(cal.ok);
  set_floor(ws, cal.floor[0], cal.floor[1]);
  const double dt = 1.0 / 30;
  const double alpha = 1 - std::exp(-dt / m.params.mapping.smoothing_tau);
  double prev[2] = {0, 0}, max_step = 0, max_target_jump = 0, prev_target[2] = {0, 0};
  int swings = 0, frames = 0, out_of_reach = 0;
  std::vector<Vec3> fk(static_cast<std::size_t>(m.skeleton.joint_count()));
  for (const auto& s : track.samples) {
    const WipFrame& f = update(m, s, ws);
    for (int foot = 0; foot < 2; ++foot) {
      max_step = std::max(max_step, std::abs(f.z[foot] - prev[foot]));
      // At foot-off and mid-swing, where the equations switch branch, the
      // targets do not jump (the gaps are faded in). Elsewhere the equations
      // themselves move fast when the foot does (checked by max_step below).
      const unsigned changes = kEventFootOff | kEventMidSwing;
      if ((f.events[0] | f.events[1]) & changes)
        max_target_jump = std::max(max_target_jump, std::abs(f.z_target[foot] - prev_target[foot]));
      prev[foot] = f.z[foot];
      prev_target[foot] = f.z_target[foot];
      swings += (f.events[foot] & kEventFootOff) ? 1 : 0;
    }
    // The solved legs put the ankles on the IK targets.
    forward_positions(m.skeleton, ws.pose, fk);
    for (int foot = 0; foot < 2; ++foot) {
      const auto& leg = m.legs[foot];
      const Vec3 hip = fk[static_cast<std::size_t>(leg.root)];
      const double reach = (fk[static_cast<std::size_t>(leg.mid)] - hip).norm() +
                           (fk[static_cast<std::size_t>(leg.end)] - fk[static_cast<std::size_t>(leg.mid)]).norm();
      const Vec3 ankle = fk[static_cast<std::size_t>(leg.end)];
      ++frames;
      if ((f.target_world[foot] - hip).norm() < reach - 1e-6) {
        ASSERT_LT((ankle - f.target_world[foot]).norm(), 1e-5) << s.time;
      } else {  // out of reach (the strike overshoot): a straight leg toward the target
        ++out_of_reach;
        ASSERT_GT((ankle - hip).normalized().dot((f.target_world[foot] - hip).normalized()), 1 - 1e-9);
      }
    }
    // Supporting feet stay on the floor.
    for (int foot = 0; foot < 2; ++foot)
      if (!in_swing(f.phase[foot])) {
        ASSERT_NEAR(f.target_world[foot].y(), m.ankle_height[foot], 1e-9);
      }
  }
  EXPECT_EQ(swings, static_cast<int>(track.swings.size()));
  EXPECT_LT(out_of_reach, frames / 20) << out_of_reach << " of " << frames << " leg targets out of reach";
  EXPECT_LE(max_step, alpha * 1.2 * m.shape.S);
  EXPECT_LT(max_target_jump, 1e-9);
}

TEST(Mapping, UpdateDoesNotAllocate) {
  const auto track = synthetic_stepping({});
  const WipModel& m = cmu_model();
  WipWorkspace ws = make_workspace(m);
  const long allocations = legwork::alloc_count::count_allocations([&] {
    for (const auto& s : track.samples) update(m, s, ws);
  });
  EXPECT_EQ(allocations, 0);
}

TEST(Speed, ComfortableSteppingGivesAboutWalkingSpeedAndTheCapHolds) {
  const WipModel& m = cmu_model();
  auto mean_speed = [&](const SyntheticOptions& o, const WipModel& model) {
    const auto run = run_wip(model, synthetic_stepping(o).samples, {true, 3.0, false});
    double sum = 0;
    int n = 0;
    for (const auto& f : run.frames)
      if (f.time > 5 && f.time < 10) sum += f.speed, ++n;
    return sum / n;
  };
  SyntheticOptions comfortable;
  EXPECT_NEAR(mean_speed(comfortable, m), 1.3, 0.2);
  SyntheticOptions frantic;
  frantic.step_height = 0.35;
  frantic.cadence = 4.0;
  frantic.pause_length = 0;
  const double fast = mean_speed(frantic, m);
  EXPECT_LE(fast, 3.5 + 1e-9);
  EXPECT_GT(fast, 2.0);
  WipParams p;
  p.mapping.speed_model = SpeedModel::StepFrequency;
  SyntheticOptions two_per_second;
  two_per_second.cadence = 2.0;
  EXPECT_NEAR(mean_speed(two_per_second, make_wip_model(m.skeleton, p)), 1.3, 0.15);
}

TEST(Synthetic, StepsAreDetectedAtSeveralRatesWithNoiseAndDrops) {
  for (double rate : {30.0, 60.0, 90.0, 120.0}) {
    SyntheticOptions o;
    o.rate = rate;
    o.asymmetry = 0.3;
    const auto track = synthetic_stepping(o);
    WipParams p;
    p.signal.rate = rate;
    const auto run = run_wip(make_wip_model(cmu_model().skeleton, p), track.samples, {true, 3.0, false});
    const auto score = score_steps(detected_swings(run.frames), track.swings, 0, o.duration);
    EXPECT_GE(score.f1, 0.95) << rate << " Hz: " << score.matched << "/" << score.true_steps << " matched, "
                              << score.detected << " detected";
  }
}

TEST(Tracker, CsvTablesNeedBothAnklesAndIncreasingTime) {
  io::TrackerTable t;
  t.time = {0.0, 0.1};
  t.points.resize(1);
  t.points[0].name = "head";
  t.points[0].position = {Vec3::Zero(), Vec3::Zero()};
  t.points[0].valid = {1, 1};
  try {
    samples_from_table(t, "steps.csv");
    FAIL();
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("steps.csv"), std::string::npos);
    EXPECT_NE(msg.find("left_ankle"), std::string::npos);
    EXPECT_NE(msg.find("head"), std::string::npos);
  }
  auto ok = table_from_samples(synthetic_stepping({}).samples);
  EXPECT_EQ(samples_from_table(ok, "x").size(), ok.time.size());
  std::swap(ok.time[5], ok.time[6]);
  EXPECT_THROW(samples_from_table(ok, "x"), Error);
}

// ---- real walking ----------------------------------------------------------

const std::vector<std::string> kSampleTrials = {"05_01", "07_01", "07_02", "07_12", "10_04", "16_15", "16_21"};

TEST(RealWalking, StepsAreDetectedAndDepthsFollowTheRealFeetOnSampleTrials) {
  const Motion cycle = extract_walk_cycle(load("cmu/bvh/walking/07_01.bvh"));
  std::vector<StepScore> scores;
  Agreement depth, baseline;
  int i = 0;
  for (const auto& name : kSampleTrials) {
    const auto e = evaluate_trial(load("cmu/bvh/walking/" + name + ".bvh"), name, cycle, {}, i++);
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

TEST(RealWalking, WalkCycleIsInPlaceAndLoops) {
  const Motion cycle = extract_walk_cycle(load("cmu/bvh/walking/07_01.bvh"));
  EXPECT_GT(cycle.duration(), 0.7);
  EXPECT_LT(cycle.duration(), 1.8);
  double max_xz = 0;
  for (int f = 0; f < cycle.frame_count(); ++f) {
    const Vec3 r = cycle.frame(f).translations[0];
    max_xz = std::max(max_xz, std::hypot(r.x(), r.z()));
  }
  EXPECT_LT(max_xz, 0.15);
  // The feet swing fore and aft about the pelvis in opposite phase.
  const auto zl = ankle_depths(cycle, kLeft), zr = ankle_depths(cycle, kRight);
  const auto [lo, hi] = std::minmax_element(zl.begin(), zl.end());
  EXPECT_GT(*hi - *lo, 0.4);
  double dot = 0;
  for (std::size_t i = 0; i < zl.size(); ++i) dot += zl[i] * zr[i];
  EXPECT_LT(dot, 0);
}

TEST(RealWalking, FullSharedSetKeepsStepF1Above90Percent) {
  LEGWORK_REQUIRE_SHARED_CMU();
  const Motion cycle = extract_walk_cycle(load("cmu/bvh/walking/07_01.bvh"));
  std::vector<StepScore> clean, noisy;
  int i = 0;
  for (const auto& entry : std::filesystem::directory_iterator(testdata::shared_cmu() / "bvh" / "walking")) {
    if (entry.path().extension() != ".bvh") continue;
    io::BvhReadOptions opt;
    opt.drop_first_frame = true;
    const auto e = evaluate_trial(io::load_bvh(entry.path().string(), opt), entry.path().stem().string(), cycle, {}, i++);
    clean.push_back(e.steps);
    noisy.push_back(e.steps_noisy);
  }
  EXPECT_GE(i, 50);
  EXPECT_GE(combine(clean).f1, 0.9);
  EXPECT_GE(combine(noisy).f1, 0.85);
}

}  // namespace
}  // namespace legwork::wip
