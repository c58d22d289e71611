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
std::string wip_job_temp(const std::string& name) {
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
  job.out = wip_job_temp("legs.bvh");
  job.csv = wip_job_temp("legs.csv");
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
  job.out = wip_job_temp("x.fbx");
  EXPECT_EQ(error_of(job), "--out '" + job.out + "' must end in .glb or .bvh");
  job.out = wip_job_temp("x.glb");
  job.calibrate = "maybe";
  EXPECT_EQ(error_of(job), "--calibrate 'maybe': expected auto, on or off");
  job.calibrate = "auto";
  job.cutoff = 20;
  EXPECT_EQ(error_of(job).rfind("--cutoff 20", 0), 0u) << error_of(job);
  EXPECT_NE(error_of(job).find("half the sample rate"), std::string::npos);
}

// The detector options: an unknown name and a detection cutoff above Nyquist
// are refused by name; the adaptive detector is what the settings carry.
TEST(WipJob, DetectorOptionsReachTheSettings) {
  eval::WipJob job;
  job.detector = "psychic";
  try {
    eval::wip_settings(job, 30);
    ADD_FAILURE() << "an unknown detector was accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "--detector 'psychic': expected 'document' (the document's thresholds) or 'adaptive'");
  }
  job.detector = "adaptive";
  job.detect_cutoff = 12;
  job.min_lift = 0.02;
  const wip::Settings s = eval::wip_settings(job, 30);
  EXPECT_EQ(s.gait.detector, wip::StepDetector::Adaptive);
  EXPECT_EQ(s.signal.detect_cutoff, 12);
  EXPECT_EQ(s.gait.min_lift, 0.02);
  job.detect_cutoff = 15;
  EXPECT_THROW(eval::wip_settings(job, 30), Error);
}

// --speed-gain: 0 (the default) leaves the detector's calibrated gain, a
// positive value overrides it for either detector.
TEST(WipJob, SpeedGainReachesTheSettingsAndZeroIsTheDetectorsGain) {
  eval::WipJob job;
  EXPECT_EQ(wip::step_speed_gain(eval::wip_settings(job, 30)), wip::kAdaptiveSpeedGain);
  job.detector = "document";
  EXPECT_EQ(wip::step_speed_gain(eval::wip_settings(job, 30)), wip::kDocumentSpeedGain);
  job.speed_gain = 3.2;
  EXPECT_EQ(wip::step_speed_gain(eval::wip_settings(job, 30)), 3.2);
}

TEST(WipJob, EvaluationOverTwoTrialsWritesItsReport) {
  eval::WipJob job;
  job.data = testdata::sample("cmu/bvh/walking").string();
  job.limit = 2;
  job.eval_out = wip_job_temp("eval");
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
  // Both detectors side by side; the default settings' detector is the one of the headline score.
  const auto& det = report["detectors"];
  ASSERT_TRUE(det.contains("document") && det.contains("adaptive")) << det.dump();
  const std::string used = report["settings"]["detector"];
  EXPECT_EQ(det[used]["strict_200ms"]["matched"], report["strict_200ms"]["matched"]);
  EXPECT_EQ(det[used]["strict_200ms"]["detected"], report["strict_200ms"]["detected"]);
  EXPECT_EQ(det[used]["strict_200ms_noisy"]["f1"], report["strict_200ms_noisy"]["f1"]);
}
