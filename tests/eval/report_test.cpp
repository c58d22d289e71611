// The evaluation report on a real run (the repo's sample CMU trials): the
// per-class winners, the per-class skating and jitter beside the truth's, and
// the goals' met / not met all follow from the run's own figures.
#include <legwork/eval/report.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/io/bvh.hpp>

#include <legwork/render/layout.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include <cmath>
#include <map>

#include "testdata.hpp"

namespace legwork::eval {
namespace {

using json = nlohmann::json;
constexpr double kTestSeconds = 3.0;

// One small run shared by the tests: three classes, both protocols, no ablation.
const EvalResult& sample_run() {
  static const EvalResult run = [] {
    const Catalogue data = read_catalogue(testdata::sample("cmu").string(), "", {"basketball", "running", "walking"});
    RunOptions opt;
    opt.ablation = false;
    opt.threads = 2;
    opt.max_test_seconds = kTestSeconds;
    return run_evaluation(data, nullptr, opt);
  }();
  return run;
}

const json& sample_report() {
  static const json report = report_json(sample_run());
  return report;
}

double num(const json& j, const std::string& key) { return j.at(key).get<double>(); }

TEST(EvalReport, PerClassWinnerIsTheLowerErrorOfTheClassFigures) {
  const json& r = sample_report();
  for (const char* p : {"cross_subject", "cross_trial"}) {
    const json& w = r.at(p).at("winners");
    int wins = 0, contests = 0;
    ASSERT_FALSE(w.at("classes").empty()) << p;
    for (const auto& [cls, parts] : w.at("classes").items())
      for (const char* part : {"full_body", "lower_body"}) {
        const std::string key = std::string(part) + "_cm";
        const double a = num(r[p]["accent"]["classes"][cls], key), i = num(r[p]["ik"]["classes"][cls], key);
        EXPECT_DOUBLE_EQ(num(parts[part], "accent"), a) << p << " " << cls << " " << part;
        EXPECT_DOUBLE_EQ(num(parts[part], "ik"), i) << p << " " << cls << " " << part;
        EXPECT_EQ(parts[part]["winner"].get<std::string>(), a < i ? "accent" : "ik") << p << " " << cls << " " << part;
        ++contests;
        wins += a < i;
      }
    EXPECT_EQ(w.at("engine_wins").get<int>(), wins) << p;
    EXPECT_EQ(w.at("contests").get<int>(), contests) << p;
  }
}

// The no-class setting (one database of every class, the class recognised)
// against the same IK baseline, class by class: its own winners table, the
// goal's value is its count, and the markdown's no-class table shows them.
TEST(EvalReport, NoClassWinnersAreTheLowerErrorOfItsClassFigures) {
  const json& r = sample_report();
  auto find = [&](const std::string& name) -> const json* {
    for (const auto& t : r["targets"])
      if (t["target"] == name) return &t;
    return nullptr;
  };
  for (const char* p : {"cross_subject", "cross_trial"}) {
    const json& w = r.at(p).at("winners_no_class");
    int wins = 0, contests = 0;
    ASSERT_FALSE(w.at("classes").empty()) << p;
    for (const auto& [cls, parts] : w.at("classes").items())
      for (const char* part : {"full_body", "lower_body"}) {
        const std::string key = std::string(part) + "_cm";
        const double n = num(r[p]["no_class"]["classes"][cls], key), i = num(r[p]["ik"]["classes"][cls], key);
        EXPECT_DOUBLE_EQ(num(parts[part], "no_class"), n) << p << " " << cls << " " << part;
        EXPECT_EQ(parts[part]["winner"].get<std::string>(), n < i ? "no_class" : "ik") << p << " " << cls << " " << part;
        ++contests;
        wins += n < i;
      }
    EXPECT_EQ(w.at("engine_wins").get<int>(), wins) << p;
    EXPECT_EQ(w.at("contests").get<int>(), contests) << p;
    const json* goal = find(std::string(p) + ": no-class setting below IK in every class, full and lower body");
    ASSERT_NE(goal, nullptr) << p;
    EXPECT_EQ((*goal)["value"].get<int>(), wins) << p;
    EXPECT_EQ((*goal)["met"].get<bool>(), wins == contests) << p;
  }
  const std::string md = report_markdown(r);
  EXPECT_NE(md.find("with no class given the engine is below the IK baseline in"), std::string::npos);
  EXPECT_NE(md.find("| IK: full / lower (cm) | winner full / lower |"), std::string::npos);
}

// The IK baseline both ways: "ik" on the database's reference skeleton at the
// user's height (what the engine gets), "ik_own" on the subject's own; the
// second winners table is against "ik_own", and the two baselines differ.
TEST(EvalReport, BothIkBaselinesAreReportedAndWinsCountAgainstEach) {
  const json& r = sample_report();
  for (const char* p : {"cross_subject", "cross_trial"}) {
    ASSERT_TRUE(r.at(p).contains("ik_own")) << p;
    const json& w = r.at(p).at("winners_own_skeleton");
    int wins = 0, contests = 0;
    bool differ = false;
    for (const auto& [cls, parts] : w.at("classes").items())
      for (const char* part : {"full_body", "lower_body"}) {
        const std::string key = std::string(part) + "_cm";
        const double a = num(r[p]["accent"]["classes"][cls], key), o = num(r[p]["ik_own"]["classes"][cls], key);
        EXPECT_DOUBLE_EQ(num(parts[part], "ik"), o) << p << " " << cls << " " << part;
        differ = differ || o != num(r[p]["ik"]["classes"][cls], key);
        ++contests;
        wins += a < o;
      }
    EXPECT_EQ(w.at("engine_wins").get<int>(), wins) << p;
    EXPECT_EQ(w.at("contests").get<int>(), contests) << p;
    EXPECT_TRUE(differ) << p << ": the two IK baselines gave the same figures";
  }
  const std::string md = report_markdown(r);
  EXPECT_NE(md.find("IK baseline, subject's own skeleton"), std::string::npos);
  EXPECT_NE(md.find("Against the IK baseline on the subject's own skeleton"), std::string::npos);
}

// The truth's skating per class, recomputed here from the BVH files of the
// class's held-out trials (same clipping as the run), equals the report's, and
// is the same whichever method it sits beside.
TEST(EvalReport, PerClassTruthSkatingMatchesTheCaptureItself) {
  const json& r = sample_report();
  const json& ct = r.at("cross_trial");
  std::map<std::string, std::vector<double>> per_class;
  for (const auto& f : ct.at("fold_results")) {
    const std::string id = f["test"][0].get<std::string>();  // "SS_TT"
    const std::string cls = f["class"].get<std::string>();
    io::BvhReadOptions o;
    o.drop_first_frame = true;
    Motion m = resample(io::load_bvh(testdata::sample("cmu/bvh/" + cls + "/" + id + ".bvh").string(), o), 90.0);
    m = trim(m, 0, std::min(m.frame_count(), static_cast<int>(std::floor(kTestSeconds * 90.0)) + 1) - 1);
    per_class[cls].push_back(100.0 * foot_skating(role_track(m), MetricOptions{}.contact_height).slide_m);
  }
  ASSERT_EQ(per_class.size(), 3u);
  for (const auto& [cls, v] : per_class) {
    double mean = 0;
    for (double x : v) mean += x / static_cast<double>(v.size());
    const json& a = ct["accent"]["classes"][cls];
    EXPECT_NEAR(num(a, "foot_skating_truth_cm"), mean, 1e-9) << cls;
    EXPECT_DOUBLE_EQ(num(a, "foot_skating_truth_cm"), num(ct["ik"]["classes"][cls], "foot_skating_truth_cm")) << cls;
    EXPECT_DOUBLE_EQ(num(a, "jitter_truth"), num(ct["ik"]["classes"][cls], "jitter_truth")) << cls;
    EXPECT_GT(mean, 0.0) << cls;  // a real capture slides a little
    EXPECT_GT(num(a, "foot_skating_cm"), 0.0) << cls;
    EXPECT_GT(num(a, "jitter"), 0.0) << cls;
  }
}

TEST(EvalReport, GoalsAreMetExactlyWhenTheirValuePassesTheGoal) {
  const json& r = sample_report();
  int issue_goals = 0;
  for (const auto& t : r.at("targets")) {
    const std::string name = t["target"].get<std::string>();
    if (t["value"].is_null()) {
      EXPECT_TRUE(t["met"].is_null() || !t["met"].get<bool>()) << name;
      continue;
    }
    const double v = t["value"].get<double>(), g = t["goal"].get<double>();
    EXPECT_EQ(t["met"].get<bool>(), t["op"] == "<=" ? v <= g : v >= g) << name;
    issue_goals += t["source"] == "issue 12";
  }
  EXPECT_GE(issue_goals, 12);
  // Spot checks: values are the run's own figures.
  auto find = [&](const std::string& name) -> const json& {
    for (const auto& t : r["targets"])
      if (t["target"] == name) return t;
    ADD_FAILURE() << "no target '" << name << "'";
    return r["targets"][0];
  };
  const json& cs = r["cross_subject"]["accent"];
  EXPECT_DOUBLE_EQ(num(find("cross-subject foot skating <= 1.5x the capture's"), "value"),
                   num(cs, "foot_skating_cm") / num(cs, "foot_skating_truth_cm"));
  EXPECT_DOUBLE_EQ(num(find("cross-subject jitter <= 1.2x the capture's"), "value"), num(cs, "jitter") / num(cs, "jitter_truth"));
  EXPECT_DOUBLE_EQ(num(find("cross_trial: engine below IK in every class, full and lower body"), "value"),
                   r["cross_trial"]["winners"]["engine_wins"].get<double>());
  // The no-class setting ran beside the per-class one: its goal is the difference of their full-body errors.
  for (const char* p : {"cross_subject", "cross_trial"}) {
    const json& nc = r[p]["no_class"];
    EXPECT_DOUBLE_EQ(num(find(std::string(p) + ": no-class setting within 1 cm of the per-class one"), "value"),
                     num(nc, "full_body_cm") - num(r[p]["accent"], "full_body_cm"));
    EXPECT_GE(num(nc, "class_accuracy"), 0.0);
    EXPECT_LE(num(nc, "class_accuracy"), 1.0);
    EXPECT_GE(num(nc, "class_switches_per_minute"), 0.0);
  }
  // Recall and load time are this run's own measurements.
  const json& sp = r["meta"]["speed"];
  EXPECT_DOUBLE_EQ(num(find("fast-search recall >= 0.95"), "value"), num(sp, "fast_recall"));
  EXPECT_GT(num(sp, "fast_recall"), 0.0);
  EXPECT_LE(num(sp, "fast_recall"), 1.0);
  EXPECT_GT(num(sp, "load_ms"), 0.0);
  EXPECT_GT(num(sp, "no_class_windows"), num(sp, "database_windows"));  // every class vs the fold's class
}

TEST(EvalReport, MarkdownAndSummaryShowWinnersAndGoals) {
  const json& r = sample_report();
  const std::string md = report_markdown(r), sum = report_summary(r);
  EXPECT_NE(md.find("winner full"), std::string::npos);
  EXPECT_NE(md.find("skating accent / IK / truth"), std::string::npos);
  EXPECT_NE(md.find("| issue 12 | cross-trial full body <= 7.0 cm |"), std::string::npos);
  EXPECT_NE(sum.find("class walking"), std::string::npos);
  EXPECT_NE(sum.find("(truth "), std::string::npos);
  for (const auto& t : r["targets"]) EXPECT_NE(sum.find(t["target"].get<std::string>()), std::string::npos);
}

}  // namespace
}  // namespace legwork::eval

namespace legwork::eval {
namespace {

TEST(EvalReport, ChartsHaveNoOverlappingLabelsOrLegendsOverData) {
  const auto dir = std::filesystem::temp_directory_path() / ("legwork-report-layout-" + std::to_string(::getpid()));
  render::LayoutRecorder layout;
  const auto written = write_report(sample_run(), dir.string());
  std::size_t charts = 0;
  for (const auto& f : written) charts += f.ends_with(".png") || f.ends_with(".svg");
  ASSERT_GT(charts, 0u);
  EXPECT_EQ(layout.pictures().size(), charts);
  for (const auto& picture : layout.pictures())
    for (const auto& problem : render::layout_problems(picture)) ADD_FAILURE() << problem;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace legwork::eval
