// `legwork eval combined` on the repo's CMU walks: every method scored against
// the capture, unreadable trials listed with their reason.
#include <legwork/eval/combined.hpp>

#include <legwork/accent/database.hpp>
#include <legwork/accent/offline/builder.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/core/types.hpp>
#include <legwork/eval/run.hpp>
#include <legwork/eval/session.hpp>
#include <legwork/io/bvh.hpp>

#include "testdata.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

using namespace legwork;

TEST(EvalCombined, ScoresEachMethodAgainstTheCaptureAndListsBadTrials) {
  eval::CombinedEvalRun run;
  run.files = {testdata::sample("cmu/bvh/walking/07_01.bvh").string(), testdata::sample("cmu/bvh/walking/16_15.bvh").string()};
  const auto bad = std::filesystem::temp_directory_path() / "legwork_eval_combined_bad.bvh";
  std::ofstream(bad) << "HIERARCHY\nROOT Hips\n{\n";
  run.files.push_back(bad.string());
  const auto report = eval::evaluate_combined(run);
  ASSERT_EQ(report["trials"].size(), 2u);
  ASSERT_EQ(report["skipped"].size(), 1u);
  EXPECT_EQ(report["skipped"][0]["trial"], "legwork_eval_combined_bad");
  EXPECT_NE(report["skipped"][0]["reason"].get<std::string>().find("legwork_eval_combined_bad.bvh"), std::string::npos);
  EXPECT_FALSE(report["methods"].contains("accent")) << "no database given";
  long frames = 0;
  for (const auto& t : report["trials"]) frames += t["frames"].get<long>();
  for (const char* m : {"ik", "combined_ik"}) {
    const auto& e = report["methods"][m];
    EXPECT_EQ(e["frames"].get<long>(), frames);
    EXPECT_GT(e["full_body_cm"].get<double>(), 1.0) << m << ": head and hands cannot give the whole body exactly";
    EXPECT_LT(e["left_hand_cm"].get<double>(), 1.0) << m << ": the wrists are on the controllers";
    EXPECT_GT(e["lower_body_cm"].get<double>(), e["full_body_cm"].get<double>()) << m << ": the legs are the hard part";
  }
  // The upper body is the IK avatar's in both: only the legs differ.
  EXPECT_NE(report["methods"]["ik"]["lower_body_cm"], report["methods"]["combined_ik"]["lower_body_cm"]);
  EXPECT_GT(report["truth_foot_skating_cm"].get<double>(), 0.0);
  const std::string table = eval::combined_table(report);
  EXPECT_NE(table.find("| combined: IK upper body + walking-in-place legs (document's mapping) |"), std::string::npos) << table;
}

// The learned legs beside the document's mapping: each trial's table is built
// from the other subjects' walks only (three subjects here), the upper body
// is the same IK avatar's, only the legs differ.
TEST(EvalCombined, LearnedLegsAreScoredWithATableWithoutTheTrialsSubject) {
  eval::CombinedEvalRun run;
  for (const char* t : {"05_01", "07_12", "16_15"})
    run.files.push_back(testdata::sample(std::string("cmu/bvh/walking/") + t + ".bvh").string());
  const auto report = eval::evaluate_combined(run);
  ASSERT_TRUE(report["methods"].contains("combined_ik_learned")) << report["methods"].dump();
  const auto& learned = report["methods"]["combined_ik_learned"];
  const auto& document = report["methods"]["combined_ik"];
  EXPECT_EQ(learned["frames"], document["frames"]);
  EXPECT_DOUBLE_EQ(learned["left_hand_cm"].get<double>(), document["left_hand_cm"].get<double>());
  EXPECT_NE(learned["lower_body_cm"], document["lower_body_cm"]);
  EXPECT_TRUE(std::isfinite(learned["foot_skating_cm"].get<double>()));
  EXPECT_NE(eval::combined_table(report).find("(learned mapping, without the trial's subject)"), std::string::npos);
}

// With a database every method gets what the engine gets: the IK avatar runs on the database's
// skeleton at the user's height, not on the held-out walker's own bone lengths.
TEST(EvalCombined, WithADatabaseTheIkBodiesUseItsSkeletonAtTheUsersHeight) {
  const std::string held_out = "bvh/walking/07_02.bvh";
  const auto db_path = std::filesystem::temp_directory_path() / ("legwork_eval_combined_walks_" + std::to_string(getpid()) + ".lwdb");
  accent::save_database(db_path.string(), accent::build_database(accent::load_trials(testdata::sample("cmu").string(), {"walking"}, {held_out}),
                                                                 accent::BuildConfig{}));
  eval::CombinedEvalRun run;
  run.files = {testdata::sample("cmu/" + held_out).string()};
  run.database = db_path.string();
  const auto report = eval::evaluate_combined(run);
  EXPECT_EQ(report["ik_skeleton"], "database skeleton at the user's height");
  ASSERT_EQ(report["trials"].size(), 1u);
  const accent::Database db = accent::load_database(db_path.string());
  io::BvhReadOptions o;
  o.drop_first_frame = true;
  const Motion truth = resample(io::load_bvh(run.files[0], o), db.feature_space().fps);
  accent::Settings s;
  s.user_height = measure_body(truth.skeleton).standing_height;
  const Skeleton body = accent::make_model(db, s).skeleton();
  double differ = 0;
  for (std::size_t j = 0; j < body.rest_offsets.size() && j < truth.skeleton.rest_offsets.size(); ++j)
    differ = std::max(differ, (body.rest_offsets[j] - truth.skeleton.rest_offsets[j]).norm());
  EXPECT_GT(differ, 0.001) << "the database's bones are not the walker's";
  const Motion ik = eval::run_ik_baseline(body, tracker_frames_from_motion(truth), db.feature_space().fps);
  EXPECT_DOUBLE_EQ(report["trials"][0]["ik"]["full_body_cm"].get<double>(),
                   eval::truth_error(ik, truth)["full_body_cm"].get<double>());
  std::filesystem::remove(db_path);
}

TEST(EvalCombined, NoTrialsIsAnError) {
  try {
    (void)eval::evaluate_combined({});
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "eval combined: no walking trials given");
  }
}
