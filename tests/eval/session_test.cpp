// Figures of one accentuated session (src/eval/session.cpp): statuses, speed,
// per-frame statistics, error against the ground truth and the session video,
// on a real CMU walk.
#include <legwork/eval/session.hpp>

#include <legwork/core/interpolate.hpp>
#include <legwork/core/tracker.hpp>
#include <legwork/render/layout.hpp>

#include "cmu_sample.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <unistd.h>

using namespace legwork;

namespace {

Motion walk() { return testdata::load_sample("cmu/bvh/walking/07_01.bvh"); }

// A run of `frames` frames whose statuses cycle Matched, Partial, Unmatched.
accent::AccentRun cycling_run(int frames, double seconds) {
  accent::AccentRun run;
  run.output = trim(walk(), 0, frames - 1);
  run.seconds = seconds;
  const accent::MatchStatus cycle[] = {accent::MatchStatus::Matched, accent::MatchStatus::Partial, accent::MatchStatus::Unmatched};
  for (int f = 0; f < frames; ++f) {
    accent::Info i;
    i.match = cycle[f % 3];
    i.match_weight = f % 3 == 0 ? 1.0 : f % 3 == 1 ? 0.5 : 0.0;
    i.fallback = 1.0 - i.match_weight;
    i.matches = {f % 3 == 2 ? 0 : 4, f % 3 == 0 ? 4 : 0};
    i.best_distance = {0.25f * static_cast<float>(f % 4), 1.0f};
    run.info.push_back(i);
  }
  return run;
}

}  // namespace

TEST(Session, FiguresCountStatusesAndAverageTheWeight) {
  const auto run = cycling_run(30, 0.5);  // 10 of each status
  const auto fig = eval::session_figures(run);
  ASSERT_EQ(fig.statuses.size(), 3u);
  for (auto s : {accent::MatchStatus::Matched, accent::MatchStatus::Partial, accent::MatchStatus::Unmatched})
    EXPECT_EQ(fig.statuses.at(accent::status_name(s)), 10) << accent::status_name(s);
  EXPECT_DOUBLE_EQ(fig.mean_match_weight, 0.5);  // (10 x 1 + 10 x 0.5 + 10 x 0) / 30
  EXPECT_DOUBLE_EQ(fig.frames_per_second, 60.0);  // 30 frames in 0.5 s
}

TEST(Session, PerFrameEntriesRepeatEachFramesInfo) {
  const auto run = cycling_run(12, 1.0);
  const auto per = eval::session_per_frame(run);
  ASSERT_EQ(per.size(), run.info.size());
  for (std::size_t f = 0; f < per.size(); ++f) {
    const auto& i = run.info[f];
    EXPECT_EQ(per[f]["status"].get<std::string>(), accent::status_name(i.match));
    EXPECT_EQ(per[f]["match_weight"].get<double>(), i.match_weight);
    EXPECT_EQ(per[f]["fallback"].get<double>(), i.fallback);
    for (std::size_t h = 0; h < 2; ++h) {
      EXPECT_EQ(per[f]["matches"][h].get<int>(), i.matches[h]);
      EXPECT_EQ(per[f]["best_distance"][h].get<float>(), i.best_distance[h]);
    }
  }
}

TEST(Session, TruthErrorIsZeroForTheTruthAndTheShiftForAShiftedBody) {
  const Motion truth = walk();
  const auto same = eval::truth_error(truth, truth);
  for (const char* k : {"left_hand_cm", "right_hand_cm", "full_body_cm", "lower_body_cm"}) EXPECT_EQ(same[k].get<double>(), 0.0) << k;
  Motion shifted = truth;
  for (int f = 0; f < shifted.frame_count(); ++f) shifted.frame(f).translations[0] += Vec3(0.1, 0, 0);
  const auto off = eval::truth_error(shifted, truth);
  for (const char* k : {"left_hand_cm", "right_hand_cm", "full_body_cm", "lower_body_cm"}) EXPECT_NEAR(off[k].get<double>(), 10.0, 1e-9) << k;
  // Sliding sideways as a whole changes no foot's slide while planted.
  EXPECT_NEAR(off["foot_skating_cm"].get<double>(), same["foot_skating_cm"].get<double>(), 1e-9);
  try {
    (void)eval::truth_error(trim(truth, 0, 9), truth);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("evaluate_trial: output has 10 frames, ground truth " + std::to_string(truth.frame_count()), 0), 0u)
        << e.what();
  }
}

TEST(Session, DescriptionPrintsEveryFigureInItsPlace) {
  const nlohmann::json e{{"left_hand_cm", 1.31}, {"right_hand_cm", 2.5}, {"full_body_cm", 7.0}, {"lower_body_cm", 9.94},
                         {"foot_skating_cm", 0.126}};
  EXPECT_EQ(eval::describe_truth_error("accent", e),
            "accent       full body 7.0 cm, lower body 9.9 cm, hands 1.3 / 2.5 cm, foot skating 0.13 cm/frame\n");
}

TEST(Session, VideoIsWrittenOrAMissingEncoderIsNamed) {
  const Motion truth = trim(walk(), 0, 29);
  const auto frames = tracker_frames_from_motion(truth);
  const auto path = (std::filesystem::temp_directory_path() / ("legwork_session_test_" + std::to_string(getpid()) + ".mp4")).string();
  std::filesystem::remove(path);
  if (std::system("command -v ffmpeg >/dev/null 2>&1") == 0) {
    eval::render_session_video(frames, truth.fps, truth, nullptr, &truth, "session test", path);
    EXPECT_GT(std::filesystem::file_size(path), 0u);
    std::filesystem::remove(path);
  }
  setenv("LEGWORK_FFMPEG", "/nonexistent/ffmpeg", 1);
  try {
    eval::render_session_video(frames, truth.fps, truth, &truth, nullptr, "session test", path + ".2.mp4");
    ADD_FAILURE() << "expected an error for a missing ffmpeg";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/ffmpeg"), std::string::npos) << e.what();
  }
  unsetenv("LEGWORK_FFMPEG");
}

// The session video's frames as drawn (title strip, a label per panel, the time
// counter in its own strip): four panels, as `accent run --compare-ik --video` on a
// trial with its truth draws them; no label over another, none outside the frame.
TEST(Session, VideoFramesHaveNoOverlappingLabels) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0) GTEST_SKIP() << "ffmpeg not installed; the video needs it";
  const Motion truth = trim(walk(), 0, 59);
  const auto frames = tracker_frames_from_motion(truth);
  const auto path = (std::filesystem::temp_directory_path() / ("legwork_session_layout_" + std::to_string(getpid()) + ".mp4")).string();
  render::LayoutRecorder rec;
  eval::render_session_video(frames, truth.fps, truth, &truth, &truth, "legwork accent: 07_01.bvh", path);
  std::filesystem::remove(path);
  // 59 / 120 s at the video's 30 fps: frames 0..14
  ASSERT_EQ(rec.pictures().size(), 15u);
  for (const auto& frame : rec.pictures()) {
    EXPECT_NE(frame.path.find(path + " frame "), std::string::npos) << frame.path;
    int labels = 0;
    bool title = false, counter = false;
    for (const auto& t : frame.texts) {
      labels += t.text == "input (head, hands)" || t.text == "accentuated" || t.text == "IK baseline" || t.text == "ground truth";
      title = title || t.text == "legwork accent: 07_01.bvh";
      counter = counter || t.text.rfind("t = ", 0) == 0;
    }
    EXPECT_EQ(labels, 4) << frame.path;
    EXPECT_TRUE(title && counter) << frame.path;
    for (const auto& problem : render::layout_problems(frame)) ADD_FAILURE() << problem;
  }
  EXPECT_EQ(rec.pictures().back().path, path + " frame 14");
}
