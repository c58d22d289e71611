// Renderer tests on real CMU data: files decode, have the requested size, are
// not blank, put the figure inside the frame, keep left/right on the correct
// side; contact sheets, trajectories and panel grids.
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/render/render.hpp>

#include "render_test_util.hpp"
#include "testdata.hpp"

#include <cstring>
#include <fstream>
#include <sstream>

using namespace legwork;
using namespace legwork::render;
using legwork::render::testing::camera;
using legwork::render::testing::Image;
using legwork::render::testing::is_background;
using legwork::render::testing::near_color;
using legwork::render::testing::out;
using legwork::render::testing::walk_07_01;
using legwork::render::testing::rendered;
using legwork::render::testing::out_dir;

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST(RenderScene, PngHasSizeContentAndFigureInsideFrame) {
  const Motion& m = walk_07_01();
  Scene s;
  s.figures.push_back(make_figure(m.skeleton, m.frame(60), 1.0, "frame 60"));
  s.title = "07_01 frame 60";
  for (View v : {View::Side, View::Front, View::ThreeQuarter, View::Top}) {
    const Camera cam = camera(v, 320, 400);
    const auto file = out("scene_" + view_name(v) + ".png");
    render_scene(s, cam, file);
    Image img(file);
    ASSERT_TRUE(img.ok()) << file;
    EXPECT_EQ(img.width(), 320);
    EXPECT_EQ(img.height(), 400);
    EXPECT_GT(img.count([](int, int, const auto& p) { return !is_background(p); }), 800) << view_name(v);
    // Every joint projects inside the picture, off its edges.
    const Framing fr = frame_scene(s, cam);
    for (const auto& p : s.figures[0].positions) {
      const auto q = fr.to_pixel(p);
      EXPECT_GT(q.x(), 5);
      EXPECT_LT(q.x(), 315);
      EXPECT_GT(q.y(), 5);
      EXPECT_LT(q.y(), 395);
    }
    // The pelvis pixel is drawn.
    const auto hip = fr.to_pixel(s.figures[0].positions[0]);
    EXPECT_FALSE(is_background(img.at(static_cast<int>(hip.x()), static_cast<int>(hip.y())))) << view_name(v);
  }
}

TEST(RenderScene, SvgHasPaths) {
  const Motion& m = walk_07_01();
  Scene s;
  s.figures.push_back(make_figure(m.skeleton, m.frame(10)));
  const auto file = out("scene.svg");
  render_scene(s, Camera{}, file);
  const auto text = slurp(file);
  EXPECT_NE(text.find("<svg"), std::string::npos);
  EXPECT_NE(text.find("<path"), std::string::npos);
}

TEST(RenderScene, BadExtensionIsAnError) {
  Scene s;
  EXPECT_THROW(render_scene(s, Camera{}, out("x.jpg")), Error);
  EXPECT_THROW(render_scene(s, Camera{}, out("no-extension")), Error);
}

// In the front view the character's left (+x) is on the picture's right: the
// left colour must be mostly on the right half and the right colour on the
// left half. Checked on the rest pose (facing +z, arms out) and on a real
// walking frame turned to face +z by the contact sheet.
TEST(RenderScene, FrontViewPutsTheLeftSideOnThePictureRight) {
  const auto& skel = walk_07_01().skeleton;
  Scene s;
  s.floor = false;
  s.figures.push_back(make_figure(skel, Pose(skel)));
  const Camera cam = camera(View::Front, 400, 400);
  const Image img = rendered(s, cam, "front_rest.png");
  ASSERT_TRUE(img.ok());
  const int w = img.width();
  auto count = [&](const Rgb& c, bool right_half) {
    return img.count([&](int x, int, const auto& p) { return (x >= w / 2) == right_half && near_color(p, c); });
  };
  const int left_on_right = count(kLeftColor, true), left_on_left = count(kLeftColor, false);
  const int right_on_left = count(kRightColor, false), right_on_right = count(kRightColor, true);
  EXPECT_GT(left_on_right, 200);
  EXPECT_GT(right_on_left, 200);
  EXPECT_LT(left_on_left, left_on_right / 10);
  EXPECT_LT(right_on_right, right_on_left / 10);
}

// A walking frame turned to walk along -z: the contact sheet's face_forward
// must turn it back, so the front row still shows the left side on the right
// (and without face_forward the picture shows the back: left on the left).
TEST(ContactSheet, FrontRowFacesTheViewerWhateverTheWalkingDirection) {
  const Motion& m = walk_07_01();
  const auto fr = m.frame(100);
  Pose p;
  p.rotations.assign(fr.rotations.begin(), fr.rotations.end());
  p.translations.assign(fr.translations.begin(), fr.translations.end());
  const Quat half_turn(Eigen::AngleAxisd(kPi, Vec3::UnitY()));
  p.rotations[0] = half_turn * p.rotations[0];
  p.translations[0] = half_turn * p.translations[0];
  auto left_minus_right_x = [&](bool face_forward) {
    SheetOptions opt;
    opt.views = {View::Front};
    opt.face_forward = face_forward;
    const auto file = out(face_forward ? "sheet_turned_ff.png" : "sheet_turned_raw.png");
    render_contact_sheet(m.skeleton, {p}, opt, file);
    Image img(file);
    EXPECT_TRUE(img.ok());
    double lx = 0, rx = 0;
    int ln = 0, rn = 0;
    for (int y = 0; y < img.height(); ++y)
      for (int x = 0; x < img.width(); ++x) {
        const auto px = img.at(x, y);
        if (near_color(px, kLeftColor)) lx += x, ++ln;
        if (near_color(px, kRightColor)) rx += x, ++rn;
      }
    EXPECT_GT(ln, 100);
    EXPECT_GT(rn, 100);
    return lx / std::max(ln, 1) - rx / std::max(rn, 1);
  };
  EXPECT_GT(left_minus_right_x(true), 10);
  EXPECT_LT(left_minus_right_x(false), -10);
}

TEST(ContactSheet, RowsPerViewPosesSideBySide) {
  const Motion& m = walk_07_01();
  std::vector<Pose> poses;
  std::vector<std::string> labels;
  for (int f = 20; f <= 120; f += 25) {
    Pose p(m.skeleton);
    sample_motion(m, f / m.fps, p.ref());
    poses.push_back(p);
    labels.push_back("frame " + std::to_string(f));
  }
  SheetOptions opt;
  opt.labels = labels;
  opt.active = 2;
  opt.title = "07_01 walk";
  opt.panel_height = 300;
  const auto file = out("sheet.png");
  render_contact_sheet(m.skeleton, poses, opt, file);
  Image img(file);
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img.height(), 2 * 300 + 34);  // two view rows plus the title strip
  EXPECT_GT(img.width(), 5 * 0.8 * 300 / 2.4);  // five poses 0.8 m apart at ~1.8 m per row height
  // Both rows (front, side) show both legs' colours.
  auto in_row = [&](const Rgb& c, int row) {
    return img.count([&](int, int y, const auto& p) { return y >= 34 + row * 300 && y < 34 + (row + 1) * 300 && near_color(p, c); });
  };
  EXPECT_GT(in_row(kLeftColor, 0), 100);
  EXPECT_GT(in_row(kRightColor, 0), 100);
  EXPECT_GT(in_row(kLeftColor, 1), 100);
  EXPECT_GT(in_row(kRightColor, 1), 100);
  EXPECT_THROW(render_contact_sheet(m.skeleton, {}, opt, file), Error);
}

TEST(Trajectory, PathDrawnWithMarks) {
  const Motion& m = walk_07_01();
  const int foot = m.skeleton.require("LeftFoot");
  const Camera cam = camera(View::Side, 800, 360);
  const auto file = out("trajectory.png");
  render_trajectory(m, foot, {30, 60, 90, 120}, cam, file);
  Image img(file);
  ASSERT_TRUE(img.ok());
  const Rgb path_color{0.10, 0.55, 0.30};
  EXPECT_GT(img.count([&](int, int, const auto& p) { return near_color(p, path_color); }), 300);
  EXPECT_THROW(render_trajectory(m, 999, {}, cam, file), Error);
  EXPECT_THROW(render_trajectory(m, foot, {m.frame_count()}, cam, file), Error);
}

TEST(RenderPanels, GridOfViewsHasEveryPanelDrawn) {
  const Motion& m = walk_07_01();
  std::vector<Panel> panels;
  for (View v : {View::Side, View::Front, View::ThreeQuarter, View::Top}) {
    Panel p;
    p.scene.figures.push_back(make_figure(m.skeleton, m.frame(80)));
    p.scene.title = view_name(v);
    p.camera = camera(v, 240, 200);
    panels.push_back(p);
  }
  const auto file = out("panels.png");
  render_panels(panels, 2, file, "four views");
  Image img(file);
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img.width(), 480);
  EXPECT_EQ(img.height(), 400 + 34);
  for (int q = 0; q < 4; ++q) {
    const int x0 = (q % 2) * 240, y0 = 34 + (q / 2) * 200;
    const int n = img.count([&](int x, int y, const auto& p) {
      return x >= x0 && x < x0 + 240 && y >= y0 + 30 && y < y0 + 200 && (near_color(p, kLeftColor) || near_color(p, kRightColor));
    });
    EXPECT_GT(n, 80) << "panel " << q;
  }
  EXPECT_THROW(render_panels({}, 2, file), Error);
}

