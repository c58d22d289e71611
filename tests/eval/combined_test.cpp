// `legwork eval combined` on the repo's CMU walks: every method scored against
// the capture, unreadable trials listed with their reason.
#include <legwork/eval/combined.hpp>

#include <legwork/core/types.hpp>

#include "testdata.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

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

TEST(EvalCombined, NoTrialsIsAnError) {
  try {
    (void)eval::evaluate_combined({});
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "eval combined: no walking trials given");
  }
}
