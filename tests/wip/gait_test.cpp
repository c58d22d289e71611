// Gait-phase state machines on scripted foot-height sequences, through the
// whole runtime (signal processing included).
#include <legwork/io/bvh.hpp>
#include <legwork/wip/wip.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <cmath>
#include <functional>
#include <random>

namespace legwork::wip {
namespace {

// The CMU avatar with the document's step detector (the reference these
// state-machine tests were written for; the adaptive one is the default).
const Model& document_model() {
  static const Model m = [] {
    Settings s;
    s.gait.detector = StepDetector::Document;
    return make_model(testdata::sample_skeleton(), s);
  }();
  return m;
}

// A frame with both ankles tracked (valid) at the given positions.
TrackerFrame feet(double t, const Vec3& left, const Vec3& right) {
  TrackerFrame f;
  f.time = t;
  f.foot(kLeft) = {left, Quat::Identity(), true};
  f.foot(kRight) = {right, Quat::Identity(), true};
  return f;
}

// A smooth lift of `height` between t0 and t1 (0 outside).
double bump(double t, double t0, double t1, double height) {
  if (t <= t0 || t >= t1) return 0;
  return height * std::pow(std::sin(kPi * (t - t0) / (t1 - t0)), 2);
}

using Heights = std::function<std::pair<double, double>(double)>;

// The same avatar with the adaptive step detector.
const Model& adaptive_model() {
  static const Model m = [] {
    Settings s;
    s.gait.detector = StepDetector::Adaptive;
    return make_model(testdata::sample_skeleton(), s);
  }();
  return m;
}

std::vector<Info> run(const Heights& h, double duration, double rate = 30.0, double floor_y = 0.1,
                      const Model& model = document_model()) {
  State st(model);
  set_floor(st, floor_y, floor_y);
  Pose pose(model.skeleton());
  std::vector<Info> out;
  for (int i = 0; i <= static_cast<int>(duration * rate); ++i) {
    const double t = i / rate;
    const auto [l, r] = h(t);
    Info info;
    EXPECT_NE(update(model, feet(t, Vec3(0.1, floor_y + l, 0), Vec3(-0.1, floor_y + r, 0)), st, pose.ref(), &info),
              UpdateStatus::Rejected);
    out.push_back(info);
  }
  return out;
}

// Distinct consecutive phases of one foot.
std::vector<GaitPhase> phases(const std::vector<Info>& frames, int foot) {
  std::vector<GaitPhase> seq;
  for (const auto& f : frames)
    if (seq.empty() || seq.back() != f.phase[foot]) seq.push_back(f.phase[foot]);
  return seq;
}

int count_events(const std::vector<Info>& frames, int foot, unsigned ev) {
  int n = 0;
  for (const auto& f : frames) n += (f.events[foot] & ev) ? 1 : 0;
  return n;
}

using P = GaitPhase;

TEST(Gait, FirstStepRunsThroughAllPhasesAndEndsWithTheFeetApart) {
  const auto frames = run([](double t) { return std::pair{bump(t, 1.0, 1.5, 0.25), 0.0}; }, 2.0);
  EXPECT_EQ(phases(frames, kLeft),
            (std::vector<P>{P::DoubleSupport, P::InitialSwing, P::MidSwing, P::TerminalSwing, P::DoubleSupport}));
  EXPECT_EQ(phases(frames, kRight), (std::vector<P>{P::DoubleSupport}));
  bool first = false;
  for (const auto& f : frames) first |= f.kind == StepKind::First && f.driver == kLeft;
  EXPECT_TRUE(first);
  const double S = document_model().shape().S;
  EXPECT_NEAR(frames.back().z_target[kLeft], 0.5 * S, 1e-12);
  EXPECT_NEAR(frames.back().z_target[kRight], -0.5 * S, 1e-12);
  EXPECT_TRUE(frames.back().walking);
}

TEST(Gait, SeveralStepsAlternateAndStopAfterOneAndAHalfSeconds) {
  // Six alternating steps of 0.45 s with 0.1 s double support, then standing.
  auto h = [](double t) {
    double l = 0, r = 0;
    for (int k = 0; k < 6; ++k) {
      const double t0 = 1.0 + 0.55 * k;
      (k % 2 == 0 ? l : r) += bump(t, t0, t0 + 0.45, 0.2);
    }
    return std::pair{l, r};
  };
  const auto frames = run(h, 7.0);
  EXPECT_EQ(count_events(frames, kLeft, kEventFootOff), 3);
  EXPECT_EQ(count_events(frames, kRight, kEventFootOff), 3);
  EXPECT_EQ(count_events(frames, kLeft, kEventFootStrike), 3);
  int firsts = 0, consecutive_starts = 0;
  for (std::size_t i = 1; i < frames.size(); ++i)
    if (frames[i].driver >= 0 && frames[i - 1].driver < 0)
      (frames[i].kind == StepKind::First ? firsts : consecutive_starts)++;
  EXPECT_EQ(firsts, 1);
  EXPECT_EQ(consecutive_starts, 5);
  // The stop rule: walking ends 1.5 s after the last landing (within a frame).
  double last_strike = 0, stop = -1;
  for (std::size_t i = 1; i < frames.size(); ++i) {
    if (frames[i].events[0] & kEventFootStrike || frames[i].events[1] & kEventFootStrike) last_strike = frames[i].time;
    if (frames[i - 1].walking && !frames[i].walking) stop = frames[i].time;
  }
  ASSERT_GT(stop, 0);
  EXPECT_NEAR(stop - last_strike, 1.5, 1.0 / 30 + 1e-9);
  EXPECT_NEAR(frames.back().z[kLeft], 0.0, 0.01);
  EXPECT_NEAR(frames.back().z[kRight], 0.0, 0.01);
  EXPECT_NEAR(frames.back().root_offset, 0.0, 0.005);
}

TEST(Gait, BothFeetUpOrOneHeldForLongDoesNotWedge) {
  // Both feet up together for 3 s (a jump or a sit), then the left foot held up 8 s, then a normal step.
  auto h = [](double t) {
    double l = bump(t, 1.0, 4.0, 0.25), r = bump(t, 1.05, 4.0, 0.25);
    if (t > 5.0 && t < 13.0) l = std::min(0.2, 0.2 * (t - 5.0) / 0.2) * std::min(1.0, (13.0 - t) / 0.2);
    r += bump(t, 14.0, 14.5, 0.2);
    return std::pair{l, r};
  };
  const auto frames = run(h, 16.0);
  for (int foot : {0, 1}) EXPECT_EQ(frames.back().phase[foot], P::DoubleSupport);
  // The held foot is in swing while held and lands once.
  bool held_in_swing = true;
  for (const auto& f : frames)
    if (f.time > 7 && f.time < 12.5) held_in_swing &= in_swing(f.phase[kLeft]);
  EXPECT_TRUE(held_in_swing);
  // The final right step is seen.
  bool right_step = false;
  for (const auto& f : frames) right_step |= f.time > 14 && (f.events[kRight] & kEventFootOff);
  EXPECT_TRUE(right_step);
  for (const auto& f : frames)
    for (int foot : {0, 1}) ASSERT_TRUE(std::isfinite(f.z[foot]) && std::isfinite(f.y[foot]));
}

TEST(Gait, JitterAroundTheHeightThresholdGivesOneSwingNotMany) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.012, 0.012);
  std::vector<double> noise(400);
  for (double& n : noise) n = jitter(rng);
  auto h = [&](double t) {
    double l = 0;
    if (t > 1.0) l = std::min(0.1, 0.1 * (t - 1.0) / 0.3) + noise[static_cast<std::size_t>(t * 30) % noise.size()];
    if (t > 6.0) l = std::max(0.0, 0.1 - 0.5 * (t - 6.0));
    return std::pair{l, 0.0};
  };
  const auto frames = run(h, 8.0);
  EXPECT_LE(count_events(frames, kLeft, kEventFootOff), 1);
  EXPECT_EQ(frames.back().phase[kLeft], P::DoubleSupport);
}

// ---- the adaptive step detector (issue 13 item 2) ---------------------------

double first_event_time(const std::vector<Info>& frames, int foot, unsigned ev, double after = 0) {
  for (const auto& f : frames)
    if (f.time > after && (f.events[foot] & ev)) return f.time;
  return NAN;
}

// Five 0.15 m steps per foot, then a 4.5 cm shuffle of the left foot: the
// adaptive detector (foot-off above 20 % of the user's apex, 3 cm here) sees
// the shuffle, the document's adaptive H1 (40 %, 6 cm) does not; both see
// every normal step, and the adaptive one sees each of them earlier.
TEST(Gait, AdaptiveDetectorSeesAShuffleTheDocumentsThresholdsMissAndFiresEarlier) {
  auto h = [](double t) {
    double l = 0, r = 0;
    for (int k = 0; k < 5; ++k) {
      l += bump(t, 1.0 + 1.2 * k, 1.5 + 1.2 * k, 0.15);
      r += bump(t, 1.6 + 1.2 * k, 2.1 + 1.2 * k, 0.15);
    }
    l += bump(t, 8.0, 8.4, 0.045);
    return std::pair{l, r};
  };
  const auto doc = run(h, 10.0), ada = run(h, 10.0, 30.0, 0.1, adaptive_model());
  for (int foot : {0, 1}) {
    EXPECT_EQ(count_events(ada, foot, kEventFootOff), foot == kLeft ? 6 : 5) << "foot " << foot;
    EXPECT_EQ(count_events(doc, foot, kEventFootOff), 5) << "foot " << foot;
  }
  EXPECT_TRUE(std::isfinite(first_event_time(ada, kLeft, kEventFootOff, 7.9)));
  EXPECT_FALSE(std::isfinite(first_event_time(doc, kLeft, kEventFootOff, 7.9)));
  // Each normal step: the adaptive foot-off is at least one frame earlier.
  for (int k = 0; k < 5; ++k) {
    const double t0 = 0.9 + 1.2 * k;
    EXPECT_LT(first_event_time(ada, kLeft, kEventFootOff, t0), first_event_time(doc, kLeft, kEventFootOff, t0) - 0.03)
        << "step " << k;
  }
}

// After a few steps the user stands on a jittery tracker (3 cm std): the
// adaptive detector's height threshold rises with the measured jitter (it
// was 3 cm on the clean track) and no step is invented while standing.
TEST(Gait, AdaptiveThresholdRisesWithTrackerJitterAndInventsNoStep) {
  std::mt19937 rng(5);
  std::normal_distribution<double> jitter(0, 0.03);
  std::vector<double> noise(900);
  for (double& n : noise) n = jitter(rng);
  auto walk = [](double t) {
    double l = 0, r = 0;
    for (int k = 0; k < 4; ++k) l += bump(t, 1.0 + 1.2 * k, 1.5 + 1.2 * k, 0.15), r += bump(t, 1.6 + 1.2 * k, 2.1 + 1.2 * k, 0.15);
    return std::pair{l, r};
  };
  auto noisy = [&](double t) {
    auto p = walk(t);
    if (t > 6.5) p.first += noise[static_cast<std::size_t>(t * 30) % noise.size()], p.second += noise[static_cast<std::size_t>(t * 30 + 7) % noise.size()];
    return p;
  };
  const auto clean = run(walk, 20.0, 30.0, 0.1, adaptive_model()), shaky = run(noisy, 20.0, 30.0, 0.1, adaptive_model());
  // Standing after the steps: the start-step height threshold (docs/wip.md), below the walking one (20 % of the apex).
  EXPECT_NEAR(clean.back().h1[kLeft], adaptive_model().settings().gait.rest_lift, 1e-9);
  EXPECT_LT(clean.back().h1[kLeft], 0.2 * clean.back().apex_estimate[kLeft]);
  EXPECT_GT(shaky.back().h1[kLeft], clean.back().h1[kLeft] + 0.02);
  int false_steps = 0;
  for (const auto& f : shaky) false_steps += f.time > 8 && ((f.events[0] | f.events[1]) & kEventFootOff) ? 1 : 0;
  EXPECT_EQ(false_steps, 0);
}

// Five 0.2 m steps per foot, 2 s standing, then a 3 cm shuffle of the left foot (a start or turn shuffle):
// below 20 % of the user's apex (4 cm), so the walking thresholds miss it; after both feet have rested for
// rest_time (0.5 s) the start-step thresholds (2 cm, 0.1 m/s) see it. The same shuffle 0.25 s after the last
// step landed is not a start step. No step is invented while standing.
TEST(Gait, StartStepThresholdsAfterRestSeeAShuffleTheWalkingThresholdsMiss) {
  auto steps = [](double t, double shuffle_at) {
    double l = 0, r = 0;
    for (int k = 0; k < 5; ++k) l += bump(t, 1.0 + 1.2 * k, 1.5 + 1.2 * k, 0.2), r += bump(t, 1.6 + 1.2 * k, 2.1 + 1.2 * k, 0.2);
    l += bump(t, shuffle_at, shuffle_at + 0.3, 0.03);
    return std::pair{l, r};
  };
  static const Model no_rest = [] {
    Settings s;
    s.gait.rest_time = 0;
    return make_model(testdata::sample_skeleton(), s);
  }();
  ASSERT_GT(adaptive_model().settings().gait.rest_time, 0);
  const Heights after_rest = [&](double t) { return steps(t, 9.0); };
  const auto with = run(after_rest, 11.0, 30.0, 0.1, adaptive_model()), without = run(after_rest, 11.0, 30.0, 0.1, no_rest);
  EXPECT_TRUE(std::isfinite(first_event_time(with, kLeft, kEventFootOff, 8.9)));
  EXPECT_FALSE(std::isfinite(first_event_time(without, kLeft, kEventFootOff, 8.9)));
  int standing = 0;
  for (const auto& f : with) standing += f.time > 7.2 && f.time < 8.95 && ((f.events[0] | f.events[1]) & kEventFootOff) ? 1 : 0;
  EXPECT_EQ(standing, 0);
  EXPECT_NEAR(with.back().h1[kLeft], adaptive_model().settings().gait.rest_lift, 1e-9) << "start-step threshold while standing";
  EXPECT_GT(without.back().h1[kLeft], 0.035) << "the walking threshold";
  // 0.25 s after the last step landed (no rest yet): the walking thresholds apply and the shuffle stays unseen.
  const Heights mid_walk = [&](double t) { return steps(t, 7.15); };
  const auto walk = run(mid_walk, 8.0, 30.0, 0.1, adaptive_model());
  EXPECT_EQ(count_events(walk, kLeft, kEventFootOff), 5);
}

TEST(Gait, LostTrackingPutsTheFootDownWithoutNan) {
  State st(document_model());
  set_floor(st, 0.0, 0.0);
  Pose pose(document_model().skeleton());
  Info f;
  bool was_swing = false, lost = false;
  for (int i = 0; i < 120; ++i) {
    const double t = i / 30.0;
    TrackerFrame s = feet(t, Vec3(0, bump(t, 0.5, 2.0, 0.25), 0), Vec3::Zero());
    const bool dropped = t > 0.9 && t < 2.5;  // tracking drops out mid-swing
    if (dropped) s.foot(kLeft) = {Vec3::Constant(std::nan("")), Quat::Identity(), false};
    EXPECT_EQ(update(document_model(), s, st, pose.ref(), &f), dropped ? UpdateStatus::Degraded : UpdateStatus::Ok) << t;
    was_swing |= in_swing(f.phase[0]);
    lost |= (f.events[0] & kEventLost) != 0;
    ASSERT_TRUE(std::isfinite(f.h[0]) && std::isfinite(f.z[0]) && std::isfinite(f.speed));
    for (const auto& q : pose.rotations) ASSERT_TRUE(std::isfinite(q.w()));
  }
  EXPECT_TRUE(was_swing);
  EXPECT_TRUE(lost);
  EXPECT_EQ(f.phase[0], P::DoubleSupport);
}

TEST(Gait, OutOfOrderSamplesAreRejectedLeavingStateAndPoseUntouched) {
  State st(document_model());
  Pose pose(document_model().skeleton());
  Info info;
  ASSERT_EQ(update(document_model(), feet(1.0, Vec3::Zero(), Vec3::Zero()), st, pose.ref(), &info), UpdateStatus::Ok);
  const Pose before = pose;
  const Info info_before = info;
  EXPECT_EQ(update(document_model(), feet(0.5, Vec3(0, 5, 0), Vec3::Zero()), st, pose.ref(), &info), UpdateStatus::Rejected);
  EXPECT_EQ(update(document_model(), feet(1.0, Vec3(0, 5, 0), Vec3::Zero()), st, pose.ref(), &info), UpdateStatus::Rejected);
  EXPECT_DOUBLE_EQ(info.time, info_before.time);
  EXPECT_NEAR(st.feet[0].h, 0.0, 1e-12);
  for (std::size_t j = 0; j < pose.rotations.size(); ++j) {
    EXPECT_EQ(pose.rotations[j].coeffs(), before.rotations[j].coeffs());
    EXPECT_EQ(pose.translations[j], before.translations[j]);
  }
}

}  // namespace
}  // namespace legwork::wip
