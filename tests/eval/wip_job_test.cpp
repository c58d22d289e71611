// `legwork wip` / `legwork wip eval` as library calls, on the repo's CMU walks.
#include <legwork/eval/wip_job.hpp>

#include <legwork/io/bvh.hpp>
#include <legwork/io/text.hpp>

#include "testdata.hpp"

#include <legwork/render/layout.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>

using namespace legwork;

namespace {
std::string temp(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / "legwork_wip_job_test";
  std::filesystem::create_directories(d);
  return (d / name).string();
}
std::string error_of(const eval::WipJob& job) {
  try {
    eval::run_wip_job(job);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(WipJob, RealWalkDrivesLegsThatWalkForward) {
  eval::WipJob job;
  job.input = testdata::sample("cmu/bvh/walking/07_01.bvh").string();
  job.out = temp("legs.bvh");
  job.csv = temp("legs.csv");
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  eval::run_wip_job(job);
  const std::string printed = testing::internal::GetCapturedStdout();
  testing::internal::GetCapturedStderr();
  EXPECT_NE(printed.find("wrote legs: " + job.out), std::string::npos) << printed;
  const Motion legs = io::load_bvh(job.out, io::BvhReadOptions{});
  const auto travel = legs.frame(legs.frame_count() - 1).translations[0] - legs.frame(0).translations[0];
  EXPECT_GT(travel.norm(), 1.0) << "the real walk's steps move the avatar";
  EXPECT_NE(io::read_text_file(job.csv).find('\n'), std::string::npos);
}

TEST(WipJob, OptionsAreCheckedByName) {
  eval::WipJob job;
  job.synthetic = true;
  EXPECT_EQ(error_of(job), "--out FILE (.glb or .bvh) is required");
  job.out = temp("x.fbx");
  EXPECT_EQ(error_of(job), "--out '" + job.out + "' must end in .glb or .bvh");
  job.out = temp("x.glb");
  job.calibrate = "maybe";
  EXPECT_EQ(error_of(job), "--calibrate 'maybe': expected auto, on or off");
  job.calibrate = "auto";
  job.cutoff = 20;
  EXPECT_EQ(error_of(job).rfind("--cutoff 20", 0), 0u) << error_of(job);
  EXPECT_NE(error_of(job).find("half the sample rate"), std::string::npos);
}

TEST(WipJob, EvaluationOverTwoTrialsWritesItsReport) {
  eval::WipJob job;
  job.data = testdata::sample("cmu/bvh/walking").string();
  job.limit = 2;
  job.eval_out = temp("eval");
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  render::LayoutRecorder layout;
  eval::run_wip_eval_job(job);
  const std::string printed = testing::internal::GetCapturedStdout();
  testing::internal::GetCapturedStderr();
  EXPECT_NE(printed.find("2 trials, strict foot-offs +-200 ms"), std::string::npos) << printed;
  // Its charts (per-trial phases, the summary) have no overlapping labels
  // and no legend over the data, by the chart layer's own layout boxes.
  EXPECT_GE(layout.pictures().size(), 3u);
  for (const auto& picture : layout.pictures())
    for (const auto& problem : render::layout_problems(picture)) ADD_FAILURE() << problem;
  const auto report = nlohmann::json::parse(io::read_text_file(job.eval_out + "/report.json"));
  EXPECT_EQ(report["trials"].get<int>(), 2);
  EXPECT_EQ(report["per_trial"].size(), 2u);
}
