// Whole-clip helpers: floor calibration, runs, the frame CSV.
#include <legwork/wip/offline/run.hpp>
#include <legwork/wip/offline/synthetic.hpp>

#include "cmu_sample.hpp"
#include "testdata.hpp"
#include "sample_walk_run.hpp"

#include <cmath>
#include <limits>

namespace legwork::wip {
namespace {

using samples::cmu_model;

TEST(Calibration, RefusesWhenTheUserIsNotStill) {
  SyntheticOptions o;
  o.stand_time = 0.2;  // stepping starts almost at once
  const auto moving = synthetic_stepping(o);
  const auto bad = calibrate_floor(moving.frames);
  EXPECT_FALSE(bad.ok);
  EXPECT_NE(bad.message.find("not standing still"), std::string::npos) << bad.message;
  o.stand_time = 3.0;
  const auto still = synthetic_stepping(o);
  const auto good = calibrate_floor(still.frames);
  ASSERT_TRUE(good.ok) << good.message;
  EXPECT_NEAR(good.floor[0], o.floor_y + o.ankle_height, 0.005);
  EXPECT_THROW(run_wip(cmu_model(), moving.frames), Error);
}

TEST(Run, SkipsRejectedFramesAndKeepsOnePosePerConsumedFrame) {
  auto frames = synthetic_stepping({}).frames;
  frames[10].time = std::numeric_limits<double>::quiet_NaN();
  frames[20].time = frames[19].time;  // repeated
  const auto run = run_wip(cmu_model(), frames);
  EXPECT_EQ(run.frames.size(), frames.size() - 2);
  EXPECT_EQ(run.motion.frame_count(), static_cast<int>(run.frames.size()));
  const std::string csv = format_info_csv(run.frames);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), static_cast<long>(run.frames.size()) + 1);
  EXPECT_EQ(csv.rfind("time,phase_left,phase_right,h_left", 0), 0u);
}

TEST(Run, MedianRateNeedsThreeFrames) {
  const auto frames = synthetic_stepping({}).frames;
  EXPECT_NEAR(median_rate(frames, "x"), 30.0, 1e-9);
  try {
    median_rate(std::span(frames).first(2), "short.csv");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "short.csv: fewer than 3 samples");
  }
}

}  // namespace
}  // namespace legwork::wip
