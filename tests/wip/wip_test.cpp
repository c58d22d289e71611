// The per-frame contract of wip::update on real CMU walking: no allocation,
// the time rules (non-finite, absurd, backward and far-future times), lost
// and absurd ankle samples, the heading from the head, and restarts that keep
// the floor calibration.
#include <legwork/wip/offline/learn.hpp>
#include <legwork/wip/offline/run.hpp>
#include <legwork/wip/offline/synthetic.hpp>
#include <legwork/wip/wip.hpp>

#include "alloc_counter.hpp"
#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <cmath>
#include <limits>
#include <random>

namespace legwork::wip {
namespace {

const Motion& walk() {
  static const Motion m = testdata::load_sample("cmu/bvh/walking/05_01.bvh");  // the longest sample walk (5 s)
  return m;
}
const Model& walk_model() {
  static const Model m = make_model(walk().skeleton);
  return m;
}
// The walk's own ankles (and head) as trackers at 30 Hz.
const std::vector<TrackerFrame>& walk_frames() {
  static const auto f = tracker_frames_from_motion(walk(), 30.0);
  return f;
}

struct Stream {
  std::vector<Info> info;
  std::vector<UpdateStatus> status;
  bool finite = true;  // every output number and pose value finite
};

bool finite_info(const Info& i) {
  bool ok = std::isfinite(i.speed) && std::isfinite(i.distance) && std::isfinite(i.root_offset) && i.root_position.allFinite();
  for (int f = 0; f < 2; ++f)
    ok = ok && std::isfinite(i.h[f]) && std::isfinite(i.v[f]) && std::isfinite(i.z[f]) && std::isfinite(i.y[f]) &&
         std::isfinite(i.z_target[f]) && i.target_world[f].allFinite();
  return ok && std::isfinite(i.turn_rate);
}

Stream run_stream(const Model& m, const std::vector<TrackerFrame>& frames) {
  Stream s;
  State st(m);
  Pose pose(m.skeleton());
  Info info;
  for (const auto& f : frames) {
    s.status.push_back(update(m, f, st, pose.ref(), &info));
    s.info.push_back(info);
    s.finite = s.finite && finite_info(info);
    for (std::size_t j = 0; j < pose.rotations.size(); ++j)
      s.finite = s.finite && pose.rotations[j].coeffs().allFinite() && pose.translations[j].allFinite();
  }
  return s;
}

int walking_frames(const Stream& s) {
  int n = 0;
  for (std::size_t i = 0; i < s.info.size(); ++i) n += s.status[i] != UpdateStatus::Rejected && s.info[i].walking;
  return n;
}

TEST(Update, AllocatesNothingPerFrameOnRealWalking) {
  for (StepDetector detector : {StepDetector::Document, StepDetector::Adaptive}) {
    Settings settings = walk_model().settings();
    settings.gait.detector = detector;
    const Model m = make_model(walk_model().skeleton(), settings);
    State st(m);
    Pose pose(m.skeleton());
    Info info;
    const auto& frames = walk_frames();
    update(m, frames[0], st, pose.ref(), &info);
    const long allocations = alloc_count::count_allocations([&] {
      for (std::size_t i = 1; i < frames.size(); ++i) update(m, frames[i], st, pose.ref(), &info);
    });
    EXPECT_EQ(allocations, 0) << "detector " << int(detector);
    // It did walk (each detector with its own calibrated step-speed gain, docs/wip.md).
    EXPECT_GT(info.distance, 1.0) << "detector " << int(detector);
  }
}

// The learned depth mapping (the shipped table, built from the shared CMU
// walks) in the same per-frame contract: no allocation, finite targets that
// swing both ways while walking.
TEST(Update, TheLearnedMappingAllocatesNothingAndSwingsTheFeetBothWays) {
  Settings settings;
  settings.mapping.depth = DepthMapping::Learned;
  const LearnedMapping table = read_learned_mapping((testdata::source_dir() / "data/wip/learned_mapping.txt").string());
  const Model m = make_model(walk().skeleton, settings, {}, &table);
  ASSERT_NE(m.learned(), nullptr);
  State st(m);
  Pose pose(m.skeleton());
  Info info;
  const auto& frames = walk_frames();
  update(m, frames[0], st, pose.ref(), &info);
  double lo[2] = {0, 0}, hi[2] = {0, 0};
  bool finite = true;
  const long allocations = alloc_count::count_allocations([&] {
    for (std::size_t i = 1; i < frames.size(); ++i) {
      update(m, frames[i], st, pose.ref(), &info);
      for (int f = 0; f < 2; ++f) lo[f] = std::min(lo[f], info.z[f]), hi[f] = std::max(hi[f], info.z[f]);
      finite = finite && finite_info(info);
    }
  });
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(finite);
  for (int f = 0; f < 2; ++f) {
    EXPECT_LT(lo[f], -0.1 * m.leg_length()) << "foot " << f << " never behind the pelvis";
    EXPECT_GT(hi[f], 0.1 * m.leg_length()) << "foot " << f << " never in front of the pelvis";
  }
}

TEST(Update, TheLearnedMappingWithoutATableIsRefusedWithAMessage) {
  Settings settings;
  settings.mapping.depth = DepthMapping::Learned;
  try {
    (void)make_model(walk().skeleton, settings);
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("learned depth mapping needs a learned table"), std::string::npos) << e.what();
  }
}

TEST(Update, ANonFiniteOrAbsurdFirstTimestampIsRejectedAndDoesNotFreezeTheStream) {
  const auto& frames = walk_frames();
  const std::vector<TrackerFrame> rest(frames.begin() + 1, frames.end());
  const int expected = walking_frames(run_stream(walk_model(), rest));
  ASSERT_GT(expected, 0);
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 1e30}) {
    auto corrupt = frames;
    corrupt[0].time = bad;
    const Stream s = run_stream(walk_model(), corrupt);
    EXPECT_EQ(s.status[0], UpdateStatus::Rejected) << bad;
    // Rejected leaves the state untouched: the rest runs exactly as if the frame were absent.
    EXPECT_EQ(walking_frames(s), expected) << bad;
    EXPECT_TRUE(s.finite);
  }
}

// Every Info field, compared exactly.
void expect_same_info(const Info& a, const Info& b, std::size_t frame) {
  EXPECT_EQ(a.time, b.time) << frame;
  for (int f = 0; f < 2; ++f) {
    EXPECT_EQ(a.phase[f], b.phase[f]) << frame;
    EXPECT_EQ(a.events[f], b.events[f]) << frame;
    EXPECT_EQ(a.h[f], b.h[f]) << frame;
    EXPECT_EQ(a.v[f], b.v[f]) << frame;
    EXPECT_EQ(a.confidence[f], b.confidence[f]) << frame;
    EXPECT_EQ(a.h1[f], b.h1[f]) << frame;
    EXPECT_EQ(a.z_target[f], b.z_target[f]) << frame;
    EXPECT_EQ(a.z[f], b.z[f]) << frame;
    EXPECT_EQ(a.y[f], b.y[f]) << frame;
    EXPECT_EQ(a.cycle[f], b.cycle[f]) << frame;
    EXPECT_EQ(a.apex_estimate[f], b.apex_estimate[f]) << frame;
    EXPECT_EQ(a.target_world[f], b.target_world[f]) << frame;
  }
  EXPECT_EQ(a.lead, b.lead) << frame;
  EXPECT_EQ(a.stride_period, b.stride_period) << frame;
  EXPECT_EQ(a.since_strike, b.since_strike) << frame;
  EXPECT_EQ(a.root_offset, b.root_offset) << frame;
  EXPECT_EQ(a.speed, b.speed) << frame;
  EXPECT_EQ(a.distance, b.distance) << frame;
  EXPECT_EQ(a.heading, b.heading) << frame;
  EXPECT_EQ(a.turn_rate, b.turn_rate) << frame;
  EXPECT_EQ(a.root_position, b.root_position) << frame;
  EXPECT_EQ(a.walking, b.walking) << frame;
  EXPECT_EQ(a.driver, b.driver) << frame;
  EXPECT_EQ(a.kind, b.kind) << frame;
  EXPECT_EQ(a.double_support_time, b.double_support_time) << frame;
}

// An empty pose (the evaluation's and the tuning's runs, which keep no poses):
// the legs are not solved, and the state and every Info field are the same as
// with a pose, frame by frame, on the real walk with lost ankle samples, a
// backward time and a restart in it. A pose of another size is still refused.
TEST(Update, WithoutAPoseTheGaitAndTargetsAreTheSameAsWithOne) {
  auto frames = walk_frames();
  for (std::size_t i = 20; i < 26; ++i) frames[i].foot(0).valid = false;  // a lost ankle
  frames.insert(frames.begin() + 60, frames[50]);                          // an old frame again (rejected)
  for (std::size_t i = 100; i < frames.size(); ++i) frames[i].time += 10.0;  // a gap longer than kMaxGap: a restart
  const Stream with = run_stream(walk_model(), frames);
  State st(walk_model());
  int walking = 0, restarts = 0, rejected = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    Info info;
    const UpdateStatus s = update(walk_model(), frames[i], st, PoseRef{}, &info);
    ASSERT_EQ(s, with.status[i]) << i;
    if (s == UpdateStatus::Rejected) {
      ++rejected;
      continue;
    }
    restarts += s == UpdateStatus::Restarted;
    walking += info.walking;
    expect_same_info(info, with.info[i], i);
  }
  EXPECT_EQ(rejected, 1);
  EXPECT_EQ(restarts, 1);
  EXPECT_GT(walking, static_cast<int>(frames.size()) / 3);  // the walk does walk
  // run_wip without poses to keep: the same Info as with them.
  RunOptions keep, skip;
  keep.calibrate = skip.calibrate = false;
  skip.keep_poses = false;
  const wip::Run a = run_wip(walk_model(), walk_frames(), keep), b = run_wip(walk_model(), walk_frames(), skip);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  EXPECT_EQ(a.motion.frame_count(), static_cast<int>(a.frames.size()));
  EXPECT_EQ(b.motion.frame_count(), 0);
  for (std::size_t i = 0; i < a.frames.size(); ++i) expect_same_info(a.frames[i], b.frames[i], i);
  // A pose that is neither empty nor the model's: refused, the state untouched.
  Pose small(walk_model().skeleton());
  small.rotations.pop_back();
  small.translations.pop_back();
  State fresh(walk_model());
  Info info;
  EXPECT_EQ(update(walk_model(), walk_frames()[0], fresh, small.ref(), &info), UpdateStatus::Rejected);
  EXPECT_FALSE(fresh.clock.started());  // the frame was not consumed
}

TEST(Update, BackwardAndRepeatedTimesAreRejectedWithoutChangingTheOutcome) {
  auto frames = walk_frames();
  std::vector<TrackerFrame> with_bad;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    with_bad.push_back(frames[i]);
    if (i % 50 == 25) {
      TrackerFrame back = frames[i - 10];  // an old frame again
      with_bad.push_back(back);
      with_bad.push_back(frames[i]);  // a duplicate
    }
  }
  const Stream clean = run_stream(walk_model(), frames), bad = run_stream(walk_model(), with_bad);
  std::vector<Info> consumed;
  for (std::size_t i = 0; i < bad.info.size(); ++i)
    if (bad.status[i] != UpdateStatus::Rejected) consumed.push_back(bad.info[i]);
  ASSERT_EQ(consumed.size(), clean.info.size());
  for (std::size_t i = 0; i < consumed.size(); ++i) {
    ASSERT_EQ(consumed[i].z[0], clean.info[i].z[0]) << i;
    ASSERT_EQ(consumed[i].events[1], clean.info[i].events[1]) << i;
  }
}

TEST(Update, AFarFutureTimeSpikeRestartsTheAvatarWhichWalksAgain) {
  auto frames = walk_frames();
  const std::size_t k = frames.size() / 3;
  frames[k].time = 1.0e6;  // accepted (a forward gap: restart), then every later time is "in the past"
  const Stream s = run_stream(walk_model(), frames);
  int rejected = 0, restarts = 0;
  for (auto st : s.status) rejected += st == UpdateStatus::Rejected, restarts += st == UpdateStatus::Restarted;
  EXPECT_EQ(restarts, 2);  // into the spike and back out of it
  EXPECT_EQ(rejected, FrameClock::kRestartFrames - 1);
  int walking_after = 0;
  for (std::size_t i = k + FrameClock::kRestartFrames + 1; i < s.info.size(); ++i) walking_after += s.info[i].walking;
  EXPECT_GT(walking_after, static_cast<int>(s.info.size() - k) / 2);
  EXPECT_TRUE(s.finite);
}

TEST(Update, ARestartKeepsTheFloorCalibrationButResetsTheGait) {
  Settings settings;
  settings.signal.floor_tau = 0;  // fixed floor: the calibration is all there is
  const Model m = make_model(walk().skeleton, settings);
  State st(m);
  set_floor(st, 0.11, 0.13);
  Pose pose(m.skeleton());
  const auto& frames = walk_frames();
  for (std::size_t i = 0; i < 60; ++i) update(m, frames[i], st, pose.ref());
  // The source's clock restarts at 0: after kRestartFrames increasing frames the avatar restarts.
  UpdateStatus last = UpdateStatus::Ok;
  for (int i = 0; i < FrameClock::kRestartFrames; ++i) last = update(m, frames[static_cast<std::size_t>(i)], st, pose.ref());
  EXPECT_EQ(last, UpdateStatus::Restarted);
  EXPECT_DOUBLE_EQ(st.feet[0].floor, 0.11);
  EXPECT_DOUBLE_EQ(st.feet[1].floor, 0.13);
  EXPECT_EQ(st.gait[0].swings, 0);
  reset(m, st);
  EXPECT_FALSE(st.feet[0].has_floor);
}

// 0.5 s of absurd but finite ankle coordinates (a tracker glitch) on real walking.
TEST(Update, HugeAnkleCoordinatesAreLostTrackingAndStepDetectionRecoversWithinOneSecond) {
  const double kRecovery = 1.0;  // s after good data returns (stated in docs/wip.md)
  const Stream clean = run_stream(walk_model(), walk_frames());
  for (double sign : {1.0, -1.0}) {
    auto frames = walk_frames();
    const double t0 = 1.0, t1 = 1.5;
    for (auto& f : frames)
      if (f.time >= t0 && f.time < t1)
        for (int s = 0; s < 2; ++s) f.foot(s).position = Vec3(0.1, sign * 1e30, sign * 1e30);
    const Stream bad = run_stream(walk_model(), frames);
    EXPECT_TRUE(bad.finite) << sign;
    std::vector<double> offs_clean, offs_bad;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const bool glitch = frames[i].time >= t0 && frames[i].time < t1;
      if (glitch) {
        EXPECT_EQ(bad.status[i], UpdateStatus::Degraded);
      }
      if (frames[i].time < t1 + kRecovery) continue;
      for (int f = 0; f < 2; ++f) {
        if (clean.info[i].events[f] & kEventFootOff) offs_clean.push_back(frames[i].time + 10 * f);
        if (bad.info[i].events[f] & kEventFootOff) offs_bad.push_back(frames[i].time + 10 * f);
      }
    }
    ASSERT_GE(offs_clean.size(), 2u);
    ASSERT_EQ(offs_bad.size(), offs_clean.size()) << sign;
    for (std::size_t i = 0; i < offs_bad.size(); ++i) EXPECT_NEAR(offs_bad[i], offs_clean[i], 1.0 / 30 + 1e-9);
  }
}

TEST(Update, NoNanFromALongCorruptedStream) {
  // Ten minutes of synthetic stepping with NaN, Inf and 1e30 samples, dropouts
  // of seconds, NaN, repeated and backward timestamps.
  SyntheticOptions o;
  o.duration = 600;
  auto frames = synthetic_stepping(o).frames;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  const double bad_values[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 1e30, -1e30};
  for (std::size_t i = 1; i < frames.size(); ++i) {
    const double r = u(rng);
    if (r < 0.01) frames[i].foot(static_cast<int>(i % 2)).position.y() = bad_values[i % 4];
    else if (r < 0.015) frames[i].time = bad_values[i % 2];
    else if (r < 0.02) frames[i].time = frames[i - 1].time;
    else if (r < 0.022) frames[i].time -= 3.0;
    // (A NaN or infinite time is not cast to int: undefined behaviour, UBSan's float-cast-overflow.)
    if (std::isfinite(frames[i].time) && static_cast<int>(frames[i].time) % 97 == 0)
      frames[i].foot(0).valid = frames[i].foot(1).valid = false;
  }
  const Stream s = run_stream(walk_model(), frames);
  EXPECT_TRUE(s.finite);
  EXPECT_GT(walking_frames(s), static_cast<int>(frames.size()) / 2);
}

TEST(Update, WalksAlongTheHeadsYawAndHoldsItWhenTheHeadIsLost) {
  const Model& m = walk_model();
  State st(m);
  Pose pose(m.skeleton());
  Info info;
  SyntheticOptions o;
  o.noise = 0;
  o.drop_rate = o.nan_rate = 0;
  o.pause_length = 0;
  auto frames = synthetic_stepping(o).frames;
  const double yaw = 0.5 * kPi;  // facing +x
  for (auto& f : frames) {
    f.head() = {Vec3(0, 1.7, 0), Quat(Eigen::AngleAxisd(yaw, Vec3::UnitY())), f.time < 10};
  }
  Vec3 at10 = Vec3::Zero();
  for (const auto& f : frames) {
    const UpdateStatus s = update(m, f, st, pose.ref(), &info);
    EXPECT_EQ(s, UpdateStatus::Ok);  // the head is not needed: its loss does not degrade the legs
    EXPECT_NEAR(info.heading, yaw, 1e-12);
    if (f.time < 10) at10 = info.root_position;
  }
  EXPECT_GT(at10.x(), 3.0);  // walked along +x
  EXPECT_NEAR(at10.z(), 0.0, 1e-9);
  EXPECT_GT(info.root_position.x(), at10.x() + 3.0);  // and kept going that way with the head lost
}

// The learned mapping's turning input: the head yaw's speed, smoothed over
// kTurnTau; a dropout is not a turn, whatever the yaw when the head returns.
TEST(Update, TurnRateIsTheHeadsYawSpeedSmoothedAndADropoutIsNoTurn) {
  const Model& m = walk_model();
  State st(m);
  Pose pose(m.skeleton());
  Info info;
  const double rate = 1.0;  // rad/s, the head turning steadily
  std::vector<double> seen;
  for (int i = 0; i <= 30 * 12; ++i) {
    const double t = i / 30.0;
    TrackerFrame f;
    f.time = t;
    const bool lost = t > 8 && t < 10;  // two seconds without the head, which turns on meanwhile
    f.head() = {Vec3(0, 1.7, 0), Quat(Eigen::AngleAxisd(rate * t, Vec3::UnitY())), !lost};
    update(m, f, st, pose.ref(), &info);
    seen.push_back(info.turn_rate);
  }
  // After 6 s (5 time constants) the smoothed rate is the true one within 1 %.
  EXPECT_NEAR(seen[30 * 6], rate, 0.01 * rate);
  // The head's return: its yaw moved by 2 rad in 2 s, still 1 rad/s.
  for (int i = 30 * 10; i < 30 * 12; ++i) EXPECT_NEAR(seen[static_cast<std::size_t>(i)], rate, 0.02) << "frame " << i;
  // Real walks: 05_01 turns (49 deg/s at its turn), 07_02 walks straight.
  auto peak = [](const char* trial) {
    const Motion w = testdata::load_sample(trial);
    const Model mm = make_model(w.skeleton);
    const Stream s = run_stream(mm, tracker_frames_from_motion(w, 30.0));
    double p = 0;
    for (const auto& i : s.info) p = std::max(p, i.turn_rate);
    return p;
  };
  const double turning = peak("cmu/bvh/walking/05_01.bvh"), straight = peak("cmu/bvh/walking/07_02.bvh");
  EXPECT_GT(turning, 3 * straight) << turning << " vs " << straight;
}

// The step-speed gain: 0 (default) = the detector's calibrated gain; a
// negative or NaN gain is refused by name.
TEST(Model, SpeedGainDefaultsToTheDetectorsAndBadOnesAreRefused) {
  Settings s = walk_model().settings();
  s.mapping.speed_gain = 0;
  s.gait.detector = StepDetector::Adaptive;
  EXPECT_EQ(step_speed_gain(s), kAdaptiveSpeedGain);
  s.gait.detector = StepDetector::Document;
  EXPECT_EQ(step_speed_gain(s), kDocumentSpeedGain);
  for (double bad : {-1.0, std::nan("")}) {
    s.mapping.speed_gain = bad;
    try {
      make_model(walk_model().skeleton(), s);
      ADD_FAILURE() << "speed gain " << bad << " accepted";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("walking-in-place settings: speed_gain ", 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find("must be >= 0 (0 = the detector's calibrated gain)"), std::string::npos);
    }
  }
}

// The start-step and steady-landing settings (Python and library users set them directly) are checked by name.
TEST(Model, BadStartStepSettingsAreRefusedNamingTheField) {
  const Settings good = walk_model().settings();
  struct Case {
    const char* name;
    double GaitSettings::*field;
  };
  for (const Case& c : {Case{"rest_time", &GaitSettings::rest_time}, Case{"rest_lift", &GaitSettings::rest_lift},
                        Case{"rest_rise", &GaitSettings::rest_rise}, Case{"rest_noise_factor", &GaitSettings::rest_noise_factor},
                        Case{"settle_time", &GaitSettings::settle_time},
                        Case{"min_swing_time", &GaitSettings::min_swing_time}})
    for (double bad : {-0.5, std::nan(""), std::numeric_limits<double>::infinity()}) {
      Settings s = good;
      s.gait.*c.field = bad;
      try {
        make_model(walk_model().skeleton(), s);
        ADD_FAILURE() << c.name << " " << bad << " accepted";
      } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.rfind(std::string("walking-in-place settings: gait.") + c.name + " ", 0), 0u) << m;
        EXPECT_NE(m.find("must be finite and >= 0 (0 = off)"), std::string::npos) << m;
      }
    }
  Settings off = good;
  off.gait.rest_time = off.gait.settle_time = off.gait.min_swing_time = 0;  // 0 = off is accepted
  EXPECT_NO_THROW(make_model(walk_model().skeleton(), off));
  Settings long_swing = good;
  long_swing.gait.min_swing_time = 1.5;  // a swing shorter than that could never land
  try {
    make_model(walk_model().skeleton(), long_swing);
    ADD_FAILURE() << "min_swing_time 1.5 accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("gait.min_swing_time 1.500000 s must be <= 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace legwork::wip
