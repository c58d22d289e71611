// Video tests: skip cleanly when ffmpeg/ffprobe are missing; otherwise count
// the frames ffprobe decodes from the MP4.
#include <legwork/core/interpolate.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/render/render.hpp>

#include "render_test_util.hpp"
#include "testdata.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>

using namespace legwork;
using namespace legwork::render;

namespace {

bool have_program(const char* name) {
  const std::string cmd = std::string("command -v ") + name + " >/dev/null 2>&1";
  return std::system(cmd.c_str()) == 0;
}

#define REQUIRE_FFMPEG()                                                                  \
  do {                                                                                    \
    if (!have_program("ffmpeg") || !have_program("ffprobe"))                              \
      GTEST_SKIP() << "ffmpeg/ffprobe not installed; video tests need them";              \
  } while (0)

// Frames ffprobe decodes, or -1.
int probe_frames(const std::string& path) {
  const std::string cmd = "ffprobe -v error -select_streams v:0 -count_frames -show_entries stream=nb_read_frames,width,height "
                          "-of csv=p=0 '" + path + "'";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return -1;
  char buf[256] = {0};
  const bool got = std::fgets(buf, sizeof buf, p) != nullptr;
  pclose(p);
  if (!got) return -1;
  int w = 0, h = 0, n = -1;
  if (std::sscanf(buf, "%d,%d,%d", &w, &h, &n) != 3) return -1;
  return n;
}

Motion short_walk(double seconds) {
  Motion m = io::load_bvh(testdata::sample("cmu/bvh/walking/07_01.bvh").string());
  return trim(m, 1, static_cast<int>(seconds * m.fps));
}

}  // namespace

TEST(Video, FrameCountMatchesDurationTimesRate) {
  REQUIRE_FFMPEG();
  const Motion m = short_walk(1.0);  // 120 Hz source, resampled to 25 fps
  VideoOptions opt;
  opt.camera.width = 320;
  opt.camera.height = 240;
  opt.fps = 25;
  opt.trace_joint = m.skeleton.require("LeftFoot");
  opt.title = "07_01";
  const auto file = (render::testing::out_dir() / "walk.mp4").string();
  std::filesystem::remove(file);
  render_video(m, opt, file);
  ASSERT_TRUE(std::filesystem::exists(file));
  EXPECT_GT(std::filesystem::file_size(file), 1000u);
  const int expected = static_cast<int>(std::floor(m.duration() * 25 + 1e-9)) + 1;
  EXPECT_EQ(probe_frames(file), expected);
}

TEST(Video, SideBySideLastsAsLongAsTheLongestMotion) {
  REQUIRE_FFMPEG();
  const Motion a = short_walk(0.5), b = short_walk(1.0);
  VideoOptions opt;
  opt.camera.width = 480;
  opt.camera.height = 240;
  opt.camera.view = View::Front;
  opt.fps = 20;
  const auto file = (render::testing::out_dir() / "side_by_side.mp4").string();
  render_video_side_by_side({&a, &b}, {"half second", "one second"}, opt, file);
  const int expected = static_cast<int>(std::floor(b.duration() * 20 + 1e-9)) + 1;
  EXPECT_EQ(probe_frames(file), expected);
}

TEST(Video, BadSizesAndMissingFfmpegAreClearErrors) {
  const Motion m = short_walk(0.2);
  VideoOptions opt;
  opt.camera.width = 321;  // odd: H.264/yuv420p cannot take it
  EXPECT_THROW(render_video(m, opt, (render::testing::out_dir() / "odd.mp4").string()), Error);
  opt.camera.width = 320;
  setenv("LEGWORK_FFMPEG", "/nonexistent/ffmpeg", 1);
  try {
    render_video(m, opt, (render::testing::out_dir() / "none.mp4").string());
    ADD_FAILURE() << "expected an error for a missing ffmpeg";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ffmpeg"), std::string::npos);
  }
  unsetenv("LEGWORK_FFMPEG");
}

TEST(Video, FfmpegFailureIsAnError) {
  REQUIRE_FFMPEG();
  const Motion m = short_walk(0.2);
  VideoOptions opt;
  opt.camera.width = 160;
  opt.camera.height = 120;
  // A directory that does not exist: ffmpeg cannot open the output and exits non-zero.
  EXPECT_THROW(render_video(m, opt, "/nonexistent-dir/x.mp4"), Error);
}

TEST(Video, OverlongClipIsRefusedBeforeStartingFfmpeg) {
  // 2 frames 3 hours apart at 240 fps: 2.6 M frames. The count must be
  // refused as a number (it used to become an int directly, overflowing for
  // long enough clips), before any encoder starts or file appears.
  Motion m = short_walk(0.1);
  m = trim(m, 0, 1);
  m.fps = 1.0 / (3 * 3600.0);
  VideoOptions opt;
  opt.camera.width = 320;
  opt.camera.height = 240;
  opt.fps = 240;
  const auto file = (render::testing::out_dir() / "overlong.mp4").string();
  std::filesystem::remove(file);
  try {
    render_video(m, opt, file);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("video '" + file + "': 10800.000000 s at 240.000000 fps is more frames than "
                                         "legwork renders (1000000)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(file));
}

namespace {
// Vertical extent (pixels) of the body's side colours in a PNG still.
int body_height(const std::string& png) {
  const render::testing::Image img(png);
  EXPECT_TRUE(img.ok()) << png;
  int top = img.height(), bottom = -1;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const auto p = img.at(x, y);
      if (render::testing::near_color(p, kLeftColor, 0.15) || render::testing::near_color(p, kRightColor, 0.15))
        top = std::min(top, y), bottom = std::max(bottom, y);
    }
  return bottom - top;
}
}  // namespace

// A real walk covers metres: one framing over the whole path draws the body
// small; following it (`follow`, `legwork render --follow`) fills the frame.
TEST(Video, FollowKeepsAWalkingBodyLargeInItsFrame) {
  REQUIRE_FFMPEG();
  const Motion m = io::load_bvh(testdata::sample("cmu/bvh/walking/07_01.bvh").string());
  int heights[2] = {0, 0};
  for (int follow = 0; follow < 2; ++follow) {
    VideoOptions opt;
    opt.camera.view = View::Side;
    opt.camera.width = 320;
    opt.camera.height = 240;
    opt.fps = 5;
    opt.follow = follow == 1;
    const auto dir = render::testing::out_dir();
    const std::string file = (dir / (follow ? "follow.mp4" : "fixed.mp4")).string();
    const std::string still = (dir / (follow ? "follow.png" : "fixed.png")).string();
    render_video(m, opt, file);
    write_video_still(file, still, m.duration() / 2);
    heights[follow] = body_height(still);
  }
  EXPECT_GT(heights[0], 20) << "the body is drawn without following too";
  EXPECT_GT(heights[1], heights[0] * 13 / 10) << "fixed " << heights[0] << " px, follow " << heights[1] << " px";
}
