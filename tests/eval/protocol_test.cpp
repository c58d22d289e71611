// Fold planning on the repo's sample data, folds never leak (plan and the
// engine's databases), and a small end-to-end run.
#include <legwork/eval/report.hpp>
#include <legwork/eval/run.hpp>
#include <legwork/io/bvh.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "testdata.hpp"

namespace legwork::eval {
namespace {

std::string sample_root() { return testdata::sample("cmu").string(); }

TEST(EvalProtocol, CrossSubjectFoldsHoldOutWholeSubjects) {
  const Catalogue c = read_catalogue(sample_root(), "", {"walking", "running", "boxing"});
  const FoldPlan plan = plan_folds(c, Protocol::CrossSubject);
  ASSERT_FALSE(plan.folds.empty());
  for (const auto& f : plan.folds) {
    EXPECT_EQ(fold_leak(f, c, c), "");
    std::set<int> test_subjects;
    for (int t : f.test) test_subjects.insert(c.trials[static_cast<std::size_t>(t)].subject);
    EXPECT_EQ(test_subjects, std::set<int>{f.held_out_subject});
    // Every trial of the class is either tested or in the database, never both.
    int members = 0;
    for (const auto& t : c.trials) members += t.cls == f.cls;
    EXPECT_EQ(static_cast<int>(f.test.size() + f.database.size()), members);
  }
  // The sample's boxing class has one subject: listed as not evaluable, with the reason.
  bool boxing_skipped = false;
  for (const auto& [cls, why] : plan.skipped)
    if (cls == "boxing") boxing_skipped = why.find("subject") != std::string::npos;
  EXPECT_TRUE(boxing_skipped);
}

TEST(EvalProtocol, CrossTrialFoldsHoldOutOneTrial) {
  const Catalogue c = read_catalogue(sample_root(), "", {"walking"});
  const FoldPlan plan = plan_folds(c, Protocol::CrossTrial);
  EXPECT_EQ(plan.folds.size(), c.trials.size());
  for (const auto& f : plan.folds) {
    ASSERT_EQ(f.test.size(), 1u);
    EXPECT_EQ(f.database.size(), c.trials.size() - 1);
    EXPECT_EQ(std::count(f.database.begin(), f.database.end(), f.test[0]), 0);
  }
}

TEST(EvalProtocol, LeakDetectorCatchesALeakyFold) {
  const Catalogue c = read_catalogue(sample_root(), "", {"walking"});
  Fold f = plan_folds(c, Protocol::CrossSubject).folds.front();
  f.database.push_back(f.test.front());
  EXPECT_NE(fold_leak(f, c, c), "");
}

// The engine's databases built for each fold hold no window of the held-out
// subject (cross-subject) or trial (cross-trial).
TEST(EvalProtocol, FoldDatabasesNeverHoldHeldOutWindows) {
  const Catalogue c = read_catalogue(sample_root(), "", {"walking", "running"});
  std::vector<accent::TrialInput> inputs;
  for (const auto& e : c.trials) {
    io::BvhReadOptions opt;
    opt.drop_first_frame = true;
    inputs.push_back({e.file, e.cls, e.subject, e.trial, io::load_bvh(e.path, opt)});
  }
  const Skeleton reference = accent::reference_skeleton(inputs);
  accent::BuildConfig cfg;
  cfg.speed_variants = 0;
  std::vector<accent::PreparedTrial> prepared;
  for (const auto& in : inputs) prepared.push_back(accent::prepare_trial(in, reference, cfg));
  int folds_checked = 0;
  for (Protocol p : {Protocol::CrossSubject, Protocol::CrossTrial}) {
    for (const auto& f : plan_folds(c, p).folds) {
      std::vector<const accent::PreparedTrial*> members;
      for (int d : f.database) members.push_back(&prepared[static_cast<std::size_t>(d)]);
      accent::Database db;
      try {
        db = accent::assemble_database(members, reference, cfg);
      } catch (const Error&) {
        continue;  // every database trial filtered out: nothing to leak
      }
      ASSERT_GT(db.window_count(), 0);
      for (int w = 0; w < db.window_count(); ++w) {
        const auto& info = db.trials()[db.source(w).trial];
        if (p == Protocol::CrossSubject) {
          ASSERT_NE(info.subject, f.held_out_subject) << f.cls << " " << f.held_out;
        }
        for (int t : f.test) ASSERT_NE(info.file, c.trials[static_cast<std::size_t>(t)].file) << f.held_out;
      }
      ++folds_checked;
    }
  }
  EXPECT_GE(folds_checked, 5);
}

TEST(EvalProtocol, QuickSubsetSpreadsOverSubjects) {
  const Catalogue c = read_catalogue(sample_root());
  const Catalogue q = quick_subset(c, 3);
  for (const auto& cls : q.classes()) {
    std::set<int> subjects, all_subjects;
    int n = 0;
    for (const auto& t : q.trials)
      if (t.cls == cls) {
        ++n;
        subjects.insert(t.subject);
      }
    for (const auto& t : c.trials)
      if (t.cls == cls) all_subjects.insert(t.subject);
    EXPECT_LE(n, 3);
    EXPECT_EQ(subjects.size(), std::min<std::size_t>(all_subjects.size(), static_cast<std::size_t>(n)));
  }
}

TEST(EvalRun, SmallRunProducesTheReportFigures) {
  Catalogue c = quick_subset(read_catalogue(sample_root(), "", {"running"}), 3);
  RunOptions opt;
  opt.max_test_seconds = 4;
  opt.quick_ablation = true;
  opt.threads = 2;
  const EvalResult r = run_evaluation(c, nullptr, opt);
  ASSERT_EQ(r.protocols.size(), 2u);
  for (const auto& p : r.protocols) {
    ASSERT_FALSE(p.folds.empty());
    for (const auto& f : p.folds) {
      const MethodFold& ik = f.methods.at("ik");
      ASSERT_TRUE(ik.ok) << ik.error;
      EXPECT_LT(ik.metrics.part_cm[static_cast<std::size_t>(Part::LeftHand)], 0.5);  // hands exact by construction
      const MethodFold& a = f.methods.at("accent");
      ASSERT_TRUE(a.ok) << a.error;
      EXPECT_TRUE(std::isfinite(a.metrics.mpjpe_cm));
      EXPECT_GT(a.frames, 0);
      EXPECT_GT(a.database_windows, 0);
    }
  }
  const auto j = report_json(r);
  for (const char* p : {"cross_subject", "cross_trial"})
    for (const char* m : {"accent", "ik"})
      for (const char* k : {"full_body_cm", "upper_body_cm", "lower_body_cm", "left_hand_cm", "right_hand_cm",
                            "hand_correlation", "mpjve_cm_s", "jitter", "frames_per_second"}) {
        ASSERT_TRUE(j[p][m][k].is_number()) << p << "." << m << "." << k;
        ASSERT_TRUE(j[p][m]["classes"]["running"][k].is_number()) << p << "." << m << ".classes.running." << k;
      }
  EXPECT_TRUE(j["cross_subject"]["ablation"]["nn"]["full_body_cm"].is_number());
  EXPECT_FALSE(report_markdown(j).empty());
}

}  // namespace
}  // namespace legwork::eval
