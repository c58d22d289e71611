// Building an accentuation database (src/accent/offline/builder.cpp) from the
// repo's sample trials: trial loading, reference skeleton, per-trial
// preparation, speed variants and window counts.
#include <legwork/accent/offline/builder.hpp>
#include <legwork/core/mirror.hpp>

#include "accent_testing.hpp"
#include "error_message.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

namespace legwork::accent {
namespace {

using testdata::message_of;

// `full` without joint `cut` and everything below it (roles re-resolved), e.g.
// a rig whose left hand was cut off.
Skeleton without_subtree(const Skeleton& full, int cut) {
  Skeleton s;
  std::vector<int> keep(static_cast<std::size_t>(full.joint_count()), -1);
  for (int j = 0; j < full.joint_count(); ++j) {
    const int p = full.parents[static_cast<std::size_t>(j)];
    if (full.is_ancestor(cut, j) || (p >= 0 && keep[static_cast<std::size_t>(p)] < 0)) continue;
    keep[static_cast<std::size_t>(j)] = s.add_joint(full.names[static_cast<std::size_t>(j)], p < 0 ? -1 : keep[static_cast<std::size_t>(p)],
                                                    full.rest_offsets[static_cast<std::size_t>(j)]);
  }
  resolve_roles(s);
  return s;
}

// Window ends run from sample window_lag(0) (the first whose window lies in
// the trial) to the last, every `hop` samples.
int windows_in(int frames, int hop) { return frames <= window_lag(0) ? 0 : (frames - 1 - window_lag(0)) / hop + 1; }

TEST(AccentBuild, AllFilteredOrEmptyInputIsAClearError) {
  BuildConfig cfg;
  cfg.correlation_threshold = 1.01;  // nothing can pass
  BuildReport report;
  try {
    (void)build_database(testing::sample_trials({"walking/07_01"}), cfg, &report);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no windows"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)build_database(std::vector<TrialInput>{}, BuildConfig{}), Error);
}

// A typo in an exclusion used to keep the held-out trial in the database silently.
TEST(AccentBuild, ExcludingATrialThatIsNotThereIsAnError) {
  const std::string data = testdata::sample("cmu").string();
  const auto message = [&](const std::vector<std::string>& classes, const std::string& exclude) {
    try {
      (void)load_trials(data, classes, {exclude});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(message({"boxing"}, "nothere.bvh"),
            "exclude 'nothere.bvh' matches no trial of '" + data +
                "' in the chosen classes (name a file as in the manifest, e.g. 'bvh/boxing/13_18.bvh', by its file name, or a pattern such as '16_*')");
  EXPECT_NE(message({"boxing"}, "bvh/walking/07_01.bvh").find("matches no trial"), std::string::npos);
  EXPECT_EQ(message({"boxing", "walking"}, "bvh/walking/07_02.bvh"), "(no error)");
  EXPECT_EQ(message({"boxing", "walking"}, "07_02.bvh"), "(no error)");
  EXPECT_EQ(load_trials(data, {"boxing"}, {"13_18.bvh"}).size(), 0u);
  // Patterns: a subject (file names) or a folder of the manifest (paths).
  const auto names = [&](const std::vector<std::string>& exclude) {
    std::vector<std::string> n;
    for (const auto& t : load_trials(data, {"walking"}, exclude)) n.push_back(std::filesystem::path(t.file).filename().string());
    return n;
  };
  const auto all = names({});
  const auto without16 = names({"16_*"});
  EXPECT_EQ(without16.size() + 2, all.size()) << "the sample has two walks of subject 16";
  for (const auto& n : without16) EXPECT_NE(n.rfind("16_", 0), 0u) << n;
  EXPECT_EQ(names({"bvh/walking/16_*.bvh"}), without16);
  EXPECT_EQ(message({"walking"}, "99_*"),
            "exclude '99_*' matches no trial of '" + data +
                "' in the chosen classes (name a file as in the manifest, e.g. 'bvh/walking/05_01.bvh', by its file name, "
                "or a pattern such as '16_*')");
}

TEST(AccentBuild, SkeletonWithoutHandsIsRejectedPerTrial) {
  auto trials = testing::sample_trials({"walking/07_01", "walking/05_01"});
  // Cut the left arm off the second trial's rig below the wrist: its left hand's role disappears.
  const Skeleton& full = trials[1].motion.skeleton;
  const Skeleton s = without_subtree(full, full.roles[Role::LeftHand]);
  ASSERT_FALSE(s.roles.has(Role::LeftHand));
  trials[1].motion = Motion(s, trials[1].motion.fps, 50);
  BuildReport report;
  const Database db = build_database(trials, BuildConfig{}, &report);
  ASSERT_EQ(report.trials.size(), 2u);
  EXPECT_TRUE(report.trials[0].kept);
  EXPECT_FALSE(report.trials[1].kept);
  EXPECT_NE(report.trials[1].reason.find("left_hand"), std::string::npos) << report.trials[1].reason;
}


// The leave-one-out path of the evaluation: prepare once, assemble per fold.
TEST(AccentFolds, PreparedTrialsAssembleFoldsWithoutTheHeldOutTrial) {
  const auto trials = testing::sample_trials({"walking/05_01", "walking/07_01", "walking/07_12", "running/09_01"});
  const Skeleton ref = reference_skeleton(trials);
  const BuildConfig cfg;
  std::vector<PreparedTrial> prepared;
  for (const auto& t : trials) prepared.push_back(prepare_trial(t, ref, cfg));
  for (std::size_t held = 0; held < prepared.size(); ++held) {
    std::vector<const PreparedTrial*> train;
    for (std::size_t i = 0; i < prepared.size(); ++i)
      if (i != held) train.push_back(&prepared[i]);
    BuildReport report;
    const Database db = assemble_database(train, ref, cfg, &report);
    EXPECT_EQ(db.skeleton().names, ref.names);
    for (int w = 0; w < db.window_count(); ++w)
      ASSERT_NE(db.trials()[db.source(w).trial].file, prepared[held].info.file) << "fold " << held << " leaks";
    int expected = 0;
    for (const auto* t : train) expected += t->kept;
    EXPECT_EQ(static_cast<int>(db.trials().size()), expected);
  }
}


TEST(AccentBuild, SpeedFactorsAreDistinctAndSpreadOverTheRange) {
  for (int variants = 0; variants <= 6; ++variants) {
    BuildConfig cfg;
    cfg.speed_variants = variants;
    cfg.speed_range = 0.5;
    const auto s = speed_factors(cfg);
    ASSERT_EQ(static_cast<int>(s.size()), variants + 1) << variants << " variants";
    EXPECT_EQ(s.front(), 1.0);
    // Every re-timed copy differs from the others: no window is added twice.
    EXPECT_EQ(std::set<double>(s.begin(), s.end()).size(), s.size()) << variants << " variants";
    for (double f : s) {
      EXPECT_GE(f, 0.5 - 1e-12);
      EXPECT_LE(f, 1.5 + 1e-12);
    }
    // The range's ends: the fastest copy as soon as there is one, the slowest from two.
    EXPECT_DOUBLE_EQ(*std::max_element(s.begin(), s.end()), variants >= 1 ? 1.5 : 1.0);
    EXPECT_DOUBLE_EQ(*std::min_element(s.begin(), s.end()), variants >= 2 ? 0.5 : 1.0);
    const auto slower = std::count_if(s.begin(), s.end(), [](double f) { return f < 1; });
    EXPECT_EQ(slower, variants / 2);
  }
}

TEST(AccentBuild, ReferenceSkeletonIsTheMostCommonRig) {
  // The DAZ ladder comes first, but two of three trials are on the CMU rig.
  const auto trials = testing::sample_trials({"climbing_ladder/14_33", "walking/07_01", "running/09_01"});
  ASSERT_NE(trials[0].motion.skeleton.names, trials[1].motion.skeleton.names);
  ASSERT_EQ(trials[1].motion.skeleton.names, trials[2].motion.skeleton.names);
  const Skeleton ref = reference_skeleton(trials);
  EXPECT_EQ(ref.names, trials[1].motion.skeleton.names);
  EXPECT_EQ(ref.rest_offsets, trials[1].motion.skeleton.rest_offsets);  // the first trial on that rig
  EXPECT_EQ(message_of([] { (void)reference_skeleton({}); }), "accent build: no trials given");
}

TEST(AccentBuild, HandFootCorrelationIsAMeanAbsoluteRAndMirrorInvariant) {
  const Motion walk = testing::sample_trial("walking/07_01").motion;
  const double r = hand_foot_correlation(walk);
  EXPECT_GE(r, 0.0);
  EXPECT_LE(r, 1.0);
  // Reflecting x -> -x flips signs and swaps sides: the mean |r| over all pairs is unchanged.
  EXPECT_NEAR(hand_foot_correlation(mirror_motion(walk)), r, 1e-9);
  // A performer frozen in one pose: nothing moves, nothing correlates.
  Motion still(walk.skeleton, walk.fps, 0);
  for (int f = 0; f < 30; ++f) still.push_back(walk.frame(0));
  EXPECT_EQ(hand_foot_correlation(still), 0.0);
}

TEST(AccentBuild, PrepareTrialPutsTheTrialOnTheReferenceAtTheTrackerRate) {
  const auto trials = testing::sample_trials({"walking/07_01", "climbing_ladder/14_33"});
  const Skeleton ref = reference_skeleton(trials);
  BuildConfig cfg;
  cfg.correlation_threshold = -1;  // keep everything: this test is about the mapping
  const PreparedTrial same = prepare_trial(trials[0], ref, cfg);
  ASSERT_TRUE(same.kept) << same.reason;
  EXPECT_EQ(same.reason, "kept");
  EXPECT_EQ(same.motion.fps, cfg.fps);
  EXPECT_NEAR(same.motion.duration(), trials[0].motion.duration(), 1.0 / cfg.fps);
  EXPECT_EQ(same.motion.skeleton.names, ref.names);
  ASSERT_EQ(same.hands[0].size(), static_cast<std::size_t>(same.motion.frame_count()));
  EXPECT_EQ(same.contacts[0].size(), same.hands[0].size());
  EXPECT_TRUE(same.mirrored_hands[0].empty());  // no mirror asked for
  const PreparedTrial daz = prepare_trial(trials[1], ref, cfg);
  ASSERT_TRUE(daz.kept) << daz.reason;
  EXPECT_EQ(daz.reason, "kept (mapped by joint roles onto the database skeleton)");
  EXPECT_EQ(daz.motion.skeleton.names, ref.names);
  TrialInput tiny = trials[0];
  tiny.motion = trim(tiny.motion, 0, window_lag(0) - 1);  // one frame short of a window
  const PreparedTrial short_one = prepare_trial(tiny, ref, cfg);
  EXPECT_FALSE(short_one.kept);
  EXPECT_EQ(short_one.reason, "too short (" + std::to_string(window_lag(0)) + " frames)");
}

TEST(AccentBuild, OneWindowPerHopPerSpeedAndMirrorCopy) {
  const auto trials = testing::sample_trials({"walking/07_01"});
  const Skeleton ref = reference_skeleton(trials);
  BuildConfig cfg;
  cfg.speed_variants = 0;
  cfg.hop = 5;
  const PreparedTrial p = prepare_trial(trials[0], ref, cfg);
  ASSERT_TRUE(p.kept) << p.reason;
  const PreparedTrial* one[] = {&p};
  BuildReport report;
  const Database db = assemble_database(one, ref, cfg, &report);
  const int expected = windows_in(p.motion.frame_count(), cfg.hop);
  EXPECT_EQ(db.window_count(), expected);
  EXPECT_EQ(report.windows, expected);
  ASSERT_EQ(report.trials.size(), 1u);
  EXPECT_EQ(report.trials[0].windows, expected);
  cfg.mirror = true;
  const PreparedTrial pm = prepare_trial(trials[0], ref, cfg);
  const PreparedTrial* both[] = {&pm};
  EXPECT_EQ(assemble_database(both, ref, cfg).window_count(), 2 * expected);
  cfg.hop = 0;
  EXPECT_EQ(message_of([&] { (void)assemble_database(both, ref, cfg); }), "accent build: hop must be at least 1 sample");
}

TEST(AccentBuild, ATrialOffTheReferenceSkeletonIsNamed) {
  const auto trials = testing::sample_trials({"walking/07_01", "climbing_ladder/14_33"});
  BuildConfig cfg;
  cfg.correlation_threshold = -1;
  // Prepared against its own rig, the ladder trial is not on the CMU reference.
  const PreparedTrial ladder = prepare_trial(trials[1], trials[1].motion.skeleton, cfg);
  ASSERT_TRUE(ladder.kept) << ladder.reason;
  const PreparedTrial* one[] = {&ladder};
  EXPECT_EQ(message_of([&] { (void)assemble_database(one, trials[0].motion.skeleton, cfg); }),
            "accent build: trial 'climbing_ladder/14_33.bvh' is not on the reference skeleton");
}

TEST(AccentBuild, LoadTrialsReadsTheManifestDroppingTheTPose) {
  const std::string data = testdata::sample("cmu").string();
  const auto boxing = load_trials(data, {"boxing"});
  ASSERT_EQ(boxing.size(), 1u);
  EXPECT_EQ(boxing[0].file, "bvh/boxing/13_18.bvh");
  EXPECT_EQ(boxing[0].cls, "boxing");
  EXPECT_EQ(boxing[0].subject, 13);
  EXPECT_EQ(boxing[0].trial, 18);
  io::BvhReadOptions all;
  const Motion whole = io::load_bvh(data + "/bvh/boxing/13_18.bvh", all);
  EXPECT_EQ(boxing[0].motion.frame_count(), whole.frame_count() - 1);
  EXPECT_EQ(message_of([] { (void)load_trials("/nonexistent/legwork-data", {}); }),
            "data folder '/nonexistent/legwork-data' does not exist");
}

}  // namespace
}  // namespace legwork::accent
