// `legwork accent run` as a library call (src/eval/accent_job.cpp): a held-out
// sample walk through a database of the other sample walks.
#include <legwork/eval/accent_job.hpp>

#include <legwork/accent/offline/builder.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/text.hpp>
#include <legwork/io/tracker_csv.hpp>

#include "error_message.hpp"
#include "testdata.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <string>

#include <unistd.h>

using namespace legwork;

namespace {

const std::string kHeldOut = "bvh/walking/07_02.bvh";

// One folder per process (ctest runs these tests in parallel processes, each
// building its database), removed when the process ends.
struct Scratch {
  std::filesystem::path dir = std::filesystem::temp_directory_path() / ("legwork_accent_job_test_" + std::to_string(getpid()));
  Scratch() { std::filesystem::create_directories(dir); }
  ~Scratch() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};
std::string accent_job_temp(const std::string& name) {
  static const Scratch scratch;
  return (scratch.dir / name).string();
}

// A database of the sample walks except the held-out one, saved once.
const std::string& database_file() {
  static const std::string path = [] {
    const auto trials = accent::load_trials(testdata::sample("cmu").string(), {"walking"}, {kHeldOut});
    const std::string p = accent_job_temp("walks.lwdb");
    accent::save_database(p, accent::build_database(trials, accent::BuildConfig{}));
    return p;
  }();
  return path;
}

eval::AccentJob held_out_job(const std::string& out) {
  eval::AccentJob job;
  job.input = testdata::sample("cmu/" + kHeldOut).string();
  job.db = database_file();
  job.out = accent_job_temp(out);
  return job;
}

std::string error_of(const eval::AccentJob& job) {
  return testdata::message_of([&] { eval::run_accent_job(job); });
}

// Runs the job with stdout captured; returns what it printed.
std::string run_quietly(const eval::AccentJob& job) {
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  try {
    eval::run_accent_job(job);
  } catch (...) {
    testing::internal::GetCapturedStderr();
    std::printf("%s", testing::internal::GetCapturedStdout().c_str());
    throw;
  }
  testing::internal::GetCapturedStderr();
  return testing::internal::GetCapturedStdout();
}

}  // namespace

TEST(AccentJob, SearchModesByName) {
  EXPECT_EQ(eval::parse_search_mode("fast"), accent::SearchMode::Fast);
  EXPECT_EQ(eval::parse_search_mode("exact"), accent::SearchMode::Exact);
  EXPECT_EQ(eval::parse_search_mode("brute"), accent::SearchMode::BruteForce);
  try {
    (void)eval::parse_search_mode("quick");
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "--mode 'quick': expected fast, exact or brute");
  }
}

TEST(AccentJob, OptionsAreCheckedByName) {
  auto job = held_out_job("x.fbx");
  EXPECT_EQ(error_of(job), "--out '" + job.out + "' must end in .glb or .bvh");
  job.out = accent_job_temp("x.bvh");
  job.video = accent_job_temp("x.avi");
  EXPECT_EQ(error_of(job), "--video '" + job.video + "' must end in .mp4");
  job.video.clear();
  job.input = accent_job_temp("session.txt");
  EXPECT_EQ(error_of(job), "--input '" + job.input + "' must be a .bvh trial or a .csv headset session");
  job = held_out_job("x.bvh");
  job.mode = "quick";
  EXPECT_EQ(error_of(job), "--mode 'quick': expected fast, exact or brute");
  job = held_out_job("x.bvh");
  job.db = accent_job_temp("missing.lwdb");
  EXPECT_NE(error_of(job).find(job.db), std::string::npos) << error_of(job);
}

TEST(AccentJob, HeldOutWalkGivesOneFramePerTrackerSampleAndItsReport) {
  auto job = held_out_job("walk.bvh");
  job.json_path = accent_job_temp("walk.json");
  job.save_session = accent_job_temp("walk_session.csv");
  job.compare_ik = true;
  const std::string printed = run_quietly(job);
  EXPECT_NE(printed.find("wrote accentuated motion: " + job.out), std::string::npos) << printed;
  EXPECT_NE(printed.find("vs ground truth:"), std::string::npos) << printed;
  const Motion out = io::load_bvh(job.out, io::BvhReadOptions{});
  const auto report = nlohmann::json::parse(io::read_text_file(job.json_path));
  const double fps = report["fps"].get<double>();
  // The input trial is resampled to the database's tracker rate: one output frame per sample.
  const Motion input = io::load_bvh(job.input, io::BvhReadOptions{});
  EXPECT_EQ(out.frame_count(), resampled_frame_count(input, fps));
  EXPECT_NEAR(out.fps, fps, 1e-3);
  EXPECT_EQ(report["frames"].get<int>(), out.frame_count());
  EXPECT_EQ(report["per_frame"].size(), static_cast<std::size_t>(out.frame_count()));
  int counted = 0;
  for (const auto& [status, n] : report["statuses"].items()) counted += n.get<int>();
  EXPECT_EQ(counted, out.frame_count());
  for (const char* method : {"accent_error", "ik_error"})
    for (const char* k : {"left_hand_cm", "right_hand_cm", "full_body_cm", "lower_body_cm"}) {
      ASSERT_TRUE(report[method].contains(k)) << method << " " << k;
      EXPECT_TRUE(std::isfinite(report[method][k].get<double>())) << method << " " << k;
    }
  // The saved headset session holds the same samples.
  const auto session = io::frames_from_table(io::read_tracker_csv(job.save_session), job.save_session,
                                             {Device::Head, Device::LeftHand, Device::RightHand});
  EXPECT_EQ(static_cast<int>(session.size()), out.frame_count());
}

TEST(AccentJob, SavedSessionReplaysOntoATargetRig) {
  auto first = held_out_job("first.bvh");
  first.save_session = accent_job_temp("replay.csv");
  run_quietly(first);
  auto replay = held_out_job("replay.bvh");
  replay.input = first.save_session;
  replay.height = 1.75;
  replay.target = testdata::sample("cmu/bvh_daz/climbing_ladder/14_33.bvh").string();
  const std::string printed = run_quietly(replay);
  EXPECT_EQ(printed.find("vs ground truth:"), std::string::npos) << "a headset session has no ground truth";
  const Motion a = io::load_bvh(first.out, io::BvhReadOptions{}), b = io::load_bvh(replay.out, io::BvhReadOptions{});
  EXPECT_EQ(b.frame_count(), a.frame_count());
  EXPECT_EQ(b.skeleton.names, io::load_bvh(replay.target, io::BvhReadOptions{}).skeleton.names);
}
