// Composed pictures on a real walk: footprints where the feet stood, frame
// sampling, picture heights that follow the content's aspect, the arc and
// top-view pictures, and the sliding video (when ffmpeg is installed).
#include <legwork/render/compose.hpp>

#include <legwork/core/fk.hpp>

#include "cmu_sample.hpp"
#include "render_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

using namespace legwork;
using namespace legwork::render;
using legwork::render::testing::Image;
using legwork::render::testing::near_color;
using legwork::render::testing::out;
using legwork::render::testing::out_dir;
using legwork::render::testing::Rgba;

namespace {

const Motion& walk() {
  static const Motion m = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  return m;
}

// Horizontal distance from p to the nearest position of joint j over frames [first, last].
double nearest_xz(const Motion& m, int j, int first, int last, const Vec3& p) {
  const auto pos = joint_positions(m);
  const auto nj = static_cast<std::size_t>(m.joint_count());
  double best = 1e9;
  for (int f = first; f <= last; ++f) {
    const Vec3 d = pos[static_cast<std::size_t>(f) * nj + static_cast<std::size_t>(j)] - p;
    best = std::min(best, std::hypot(d.x(), d.z()));
  }
  return best;
}

}  // namespace

TEST(Compose, FootprintsLieUnderTheirOwnAnkleAlongTheWalk) {
  const Motion& m = walk();
  const int last = m.frame_count() - 1;
  const auto prints = detect_footprints(m, 0, last);
  const auto& r = m.skeleton.roles;
  const Vec3 travel = m.frame(last).translations[0] - m.frame(0).translations[0];
  const Eigen::Vector2d dir = Eigen::Vector2d(travel.x(), travel.z()).normalized();
  int left = 0, right = 0;
  for (const auto& fp : prints) {
    (fp.left ? left : right) += 1;
    EXPECT_EQ(fp.position.y(), 0.0);
    const int own = r[fp.left ? Role::LeftAnkle : Role::RightAnkle], other = r[fp.left ? Role::RightAnkle : Role::LeftAnkle];
    const double d_own = nearest_xz(m, own, 0, last, fp.position);
    EXPECT_LT(d_own, 0.1);  // the mean of a planted ankle, 3 cm ahead
    // The other foot passes by, but never stands, on this print: it is further away.
    EXPECT_LT(d_own, nearest_xz(m, other, 0, last, fp.position));
    // Soles point the way the walk goes (within 35 degrees).
    EXPECT_GT(Eigen::Vector2d(std::sin(fp.heading), std::cos(fp.heading)).dot(dir), std::cos(deg2rad(35)));
  }
  // A walk of several metres has several steps of each foot.
  EXPECT_GE(travel.norm(), 2.0);
  EXPECT_GE(left, 2);
  EXPECT_GE(right, 2);
  // A sub-range gives only prints of that range; an empty range or a rig without ankles gives none.
  const auto half = detect_footprints(m, 0, last / 2);
  EXPECT_LT(half.size(), prints.size());
  for (const auto& fp : half)
    EXPECT_LT(nearest_xz(m, r[fp.left ? Role::LeftAnkle : Role::RightAnkle], 0, last / 2, fp.position), 0.1);
  EXPECT_TRUE(detect_footprints(m, 10, 5).empty());
  Skeleton devices;
  devices.add_joint("Head", -1, Vec3(0, 1.6, 0));
  resolve_roles(devices);
  EXPECT_TRUE(detect_footprints(Motion(devices, 30, 10), 0, 9).empty());
}

TEST(Compose, SampleFrames) {
  // every <= 0: up to six frames evenly from first to last, both included.
  EXPECT_EQ(sample_frames(0, 100, 0), (std::vector<int>{0, 20, 40, 60, 80, 100}));
  EXPECT_EQ(sample_frames(5, 7, -1), (std::vector<int>{5, 6, 7}));
  EXPECT_EQ(sample_frames(4, 4, 0), std::vector<int>{4});
  // every > 0: first, first + every, ...; the last frame is added unless it is closer than every/2.
  EXPECT_EQ(sample_frames(0, 10, 4), (std::vector<int>{0, 4, 8, 10}));
  EXPECT_EQ(sample_frames(0, 9, 4), (std::vector<int>{0, 4, 8}));
  EXPECT_EQ(sample_frames(3, 12, 3), (std::vector<int>{3, 6, 9, 12}));
}

TEST(Compose, FittedHeightFollowsTheContentsAspect) {
  const Motion& m = walk();
  const int last = m.frame_count() - 1;
  for (View v : {View::Side, View::Front, View::ThreeQuarter, View::Top})
    for (int w : {200, 640, 1600}) {
      const int h = fitted_height(m, 0, last, v, w);
      EXPECT_EQ(h % 2, 0);
      EXPECT_GE(h, 240);
      EXPECT_LE(h, 960);
    }
  // One standing frame seen from the front is much taller than wide; the whole
  // walk seen from above is a long thin strip: its picture is flatter.
  EXPECT_GT(fitted_height(m, 0, 0, View::Front, 400), fitted_height(m, 0, last, View::Top, 400));
  // A wider picture of the same content is never less tall.
  EXPECT_LE(fitted_height(m, 0, 0, View::Side, 200), fitted_height(m, 0, 0, View::Side, 400));
}

TEST(Compose, ArcPictureHasBothViewsAndTheArc) {
  const Motion& m = walk();
  std::vector<Pose> ghosts;
  Curve arc;
  const int hand = m.skeleton.require("LeftHand");
  for (int f = 0; f < 60; f += 15) {
    Pose p(m.skeleton);
    for (int j = 0; j < m.joint_count(); ++j) {
      p.rotations[static_cast<std::size_t>(j)] = m.frame(f).rotations[static_cast<std::size_t>(j)];
      p.translations[static_cast<std::size_t>(j)] = m.frame(f).translations[static_cast<std::size_t>(j)];
    }
    arc.points.push_back(joint_positions(m.skeleton, p.ref())[static_cast<std::size_t>(hand)]);
    arc.marks.push_back(static_cast<int>(ghosts.size()));
    ghosts.push_back(p);
  }
  const std::string base = out("compose_arc");
  std::filesystem::remove(base + ".png");
  std::filesystem::remove(base + ".svg");
  render_arc(m.skeleton, ghosts, arc, "left hand arc", base);
  EXPECT_TRUE(std::filesystem::exists(base + ".svg"));
  const Image img(base + ".png");
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img.width(), 2 * 480);
  EXPECT_EQ(img.height(), 480 + 34);  // two 480 px panels under the title strip
  for (int half : {0, 1})
    EXPECT_GT(img.count([&](int x, int, const Rgba& p) { return x / 480 == half && near_color(p, kTraceColor); }), 30)
        << "the arc in panel " << half;
}

TEST(Compose, WalkFromAboveShowsTheRootTrackAndFootprints) {
  const Motion& m = walk();
  const auto prints = detect_footprints(m, 0, m.frame_count() - 1);
  const std::string path = out("compose_walk_top.png");
  render_walk_top(m, nullptr, prints, "07_01 from above", path);
  const Image img(path);
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img.width(), 800);
  EXPECT_EQ(img.height(), 800);
  EXPECT_GT(img.count([](int, int, const Rgba& p) { return near_color(p, kTraceColor); }), 200);
  // Soles are filled with their side's colour at a quarter opacity over white.
  auto fill = [](const Rgb& c) { return Rgb{1 - 0.25 * (1 - c[0]), 1 - 0.25 * (1 - c[1]), 1 - 0.25 * (1 - c[2])}; };
  Eigen::Vector2d mean[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  int n[2] = {0, 0};
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x)
      for (int side = 0; side < 2; ++side)
        if (near_color(img.at(x, y), fill(side == 0 ? kLeftColor : kRightColor), 0.03)) mean[side] += Eigen::Vector2d(x, y), ++n[side];
  ASSERT_GT(n[0], 10);
  ASSERT_GT(n[1], 10);
  // Left soles are on the walker's left. Top view: picture right = +z, up = +x
  // (pixels y down), so the walker's left (dz, -dx) of a heading (dx, dz) is the pixel direction (-dx, -dz).
  const Vec3 travel = m.frame(m.frame_count() - 1).translations[0] - m.frame(0).translations[0];
  const Eigen::Vector2d left_px(-travel.x(), -travel.z());
  EXPECT_GT((mean[0] / n[0] - mean[1] / n[1]).dot(left_px.normalized()), 5.0);
  // With a path, the path is drawn in grey.
  const std::vector<Vec3> route = {m.frame(0).translations[0], m.frame(m.frame_count() - 1).translations[0]};
  render_walk_top(m, &route, {}, "", path);
  const Image with_path(path);
  EXPECT_GT(with_path.count([](int, int, const Rgba& p) { return near_color(p, {0.6, 0.6, 0.6}, 0.03); }), 200);
}

TEST(Compose, SlideVideo) {
  if (std::system("ffmpeg -version > /dev/null 2>&1") != 0) GTEST_SKIP() << "ffmpeg not installed";
  const Motion& m = walk();
  SlideVideo v;
  for (int k = 0; k < 3; ++k) {
    Pose p(m.skeleton);
    v.key_poses.push_back(p);
    v.labels.push_back("key " + std::to_string(k));
    v.key_times.push_back(k * 0.5);
  }
  v.duration = 1.0;
  v.sample = [&](double t, PoseRef pose_out) {
    const int f = std::min(m.frame_count() - 1, static_cast<int>(t * m.fps));
    std::copy(m.frame(f).rotations.begin(), m.frame(f).rotations.end(), pose_out.rotations.begin());
    std::copy(m.frame(f).translations.begin(), m.frame(f).translations.end(), pose_out.translations.begin());
  };
  const std::string path = out("compose_slide.mp4");
  std::filesystem::remove(path);
  render_slide_video(m.skeleton, v, path);
  ASSERT_TRUE(std::filesystem::exists(path));
  EXPECT_GT(std::filesystem::file_size(path), 1000u);
  const std::string bad = (out_dir() / "no-such-folder" / "x.mp4").string();
  try {
    render_slide_video(m.skeleton, v, bad);
    ADD_FAILURE() << "no error for an unwritable video";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "ffmpeg failed writing '" + bad + "' (is ffmpeg installed?)");
  }
}
