// `legwork walkcycle` as a library call: the walk, its files and report, and
// extraction from a real CMU walk, on the shipped keys and sample data.
#include <legwork/walkcycle/offline/job.hpp>

#include <legwork/io/bvh.hpp>
#include <legwork/io/text.hpp>
#include <legwork/render/layout.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <vector>

using namespace legwork;

namespace {
std::string temp(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / "legwork_walk_job_test";
  std::filesystem::create_directories(d);
  return (d / name).string();
}
}  // namespace

TEST(WalkJob, WritesTheWalkAndAReportThatDescribesIt) {
  walkcycle::WalkJob job;
  job.keys = testdata::walk_keys_file("normal");
  job.straight = 3.0;
  job.out = temp("normal.bvh");
  job.report = temp("normal.json");
  testing::internal::CaptureStdout();
  walkcycle::run_walk_job(job);
  const std::string printed = testing::internal::GetCapturedStdout();
  EXPECT_NE(printed.find("wrote walk: " + job.out), std::string::npos) << printed;
  const auto report = nlohmann::json::parse(io::read_text_file(job.report));
  const Motion walk = io::load_bvh(job.out, io::BvhReadOptions{});
  EXPECT_EQ(report["frames"].get<int>(), walk.frame_count());
  EXPECT_GE(report["steps"].get<int>(), 4);
  EXPECT_LT(report["stance_slip_mm_max"].get<double>(), 0.01);
  // The root ends where the path does (3 m ahead, +z).
  EXPECT_NEAR(walk.frame(walk.frame_count() - 1).translations[0].z() - walk.frame(0).translations[0].z(), 3.0, 0.05);
}

TEST(WalkJob, RefusesJobsThatWriteNothingOrMixPaths) {
  walkcycle::WalkJob job;
  job.keys = testdata::walk_keys_file("normal");
  try {
    walkcycle::run_walk_job(job);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "walkcycle: nothing to write; give --out (and/or --cycle-out, --sheet, --arc, --video, --report)");
  }
  job.out = temp("x.bvh");
  job.straight = 2;
  job.path = testdata::source_dir() / "data/walks/paths/quarter-turn.json";
  try {
    walkcycle::run_walk_job(job);
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "walkcycle: give one of --path, --svg-path, --straight, --steps");
  }
}

TEST(WalkJob, ExtractsKeysFromARealWalkThatWalkAgain) {
  walkcycle::ExtractJob ex;
  ex.input = testdata::sample("cmu/bvh/walking/07_01.bvh").string();
  ex.out = temp("07_01_keys.json");
  testing::internal::CaptureStdout();
  walkcycle::run_extract_job(ex);
  walkcycle::WalkJob job;
  job.keys = ex.out;
  job.steps = 4;
  job.report = temp("07_01_walk.json");
  walkcycle::run_walk_job(job);
  testing::internal::GetCapturedStdout();
  const auto report = nlohmann::json::parse(io::read_text_file(job.report));
  EXPECT_EQ(report["steps"].get<int>(), 4);
}

// The layout of every picture (and video frame) a walk job draws, its printing kept quiet.
static std::vector<render::PictureLayout> layout_of_walk_job(const walkcycle::WalkJob& job) {
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  render::LayoutRecorder layout;
  walkcycle::run_walk_job(job);
  testing::internal::GetCapturedStdout();
  testing::internal::GetCapturedStderr();
  return layout.pictures();
}

// The demo's pictures of each shipped walk (key sheet, arcs, top view) as the
// demo draws them: no label over another label, none outside the picture,
// by the drawing layer's own layout boxes.
TEST(WalkJob, PicturesOfTheShippedWalksHaveNoOverlappingLabels) {
  for (const std::string w : {"normal", "sneak", "double-bounce"}) {
    walkcycle::WalkJob job;
    job.keys = testdata::walk_keys_file(w);
    job.path = testdata::sample("walks/paths/quarter-turn.json").string();
    job.sheet = temp(w + "_keys.png");
    job.arc = "LeftHand,LeftToeBase";
    job.arc_out = temp(w);
    job.top = temp(w + "_top.png");
    const auto pictures = layout_of_walk_job(job);
    EXPECT_GE(pictures.size(), 4u) << w;
    for (const auto& picture : pictures) {
      EXPECT_GE(picture.texts.size(), 3u) << picture.path << ": its title and labels were recorded";
      for (const auto& problem : render::layout_problems(picture)) ADD_FAILURE() << problem;
    }
  }
}

// A walk's video frames as drawn (the demo's walk videos): the time counter and
// the labels stay apart and inside the frame.
TEST(WalkJob, VideoFramesOfAShippedWalkHaveNoOverlappingLabels) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) GTEST_SKIP() << "ffmpeg not installed; the video needs it";
  walkcycle::WalkJob job;
  job.keys = testdata::walk_keys_file("normal");
  job.steps = 2;
  job.video = temp("normal_layout.mp4");
  const auto pictures = layout_of_walk_job(job);
  ASSERT_GE(pictures.size(), 10u) << "frames recorded";
  for (const auto& frame : pictures) {
    EXPECT_NE(frame.path.find(job.video + " frame "), std::string::npos) << frame.path;
    bool counter = false;
    for (const auto& t : frame.texts) counter = counter || t.text.rfind("t = ", 0) == 0;
    EXPECT_TRUE(counter) << frame.path << ": the time counter was recorded";
    for (const auto& problem : render::layout_problems(frame)) ADD_FAILURE() << problem;
  }
}
