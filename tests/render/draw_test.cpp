// Drawing a scene: curves (segments, gaps at non-finite points), bones and
// side colours, translucent figures, the floor line, footprints, device
// markers, checked on pixels at positions derived from the framing.
#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/render/render.hpp>

#include "../../src/render/scene_draw.hpp"
#include "render_test_util.hpp"
#include "testdata.hpp"

#include <algorithm>

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
using legwork::render::testing::Rgba;

namespace {

Rgba pixel(const Image& img, const Eigen::Vector2d& q) { return img.at(static_cast<int>(q.x()), static_cast<int>(q.y())); }

// A scene without floor holding one dark blue 3 px curve through `points`.
Scene ink_curve(std::vector<Vec3> points) {
  Scene s;
  s.floor = false;
  Curve c;
  c.points = std::move(points);
  c.color = {0.1, 0.1, 0.6};
  c.width = 3;
  s.curves.push_back(c);
  return s;
}

double brightness(const Rgba& p) { return (p.r + p.g + p.b) / 3; }

}  // namespace

TEST(RenderScene, NonFinitePositionsAreSkippedNotFatal) {
  const Motion& m = walk_07_01();
  Scene s;
  Figure f = make_figure(m.skeleton, m.frame(40), 1.0, "broken hand");
  f.positions[static_cast<std::size_t>(m.skeleton.require("LeftHand"))] = Vec3::Constant(std::nan(""));
  s.figures.push_back(f);
  s.footprints.push_back({Vec3(std::nan(""), 0, 0), 0.0, true});
  const auto file = out("nan.png");
  ASSERT_NO_THROW(render_scene(s, Camera{}, file));
  Image img(file);
  ASSERT_TRUE(img.ok());
  EXPECT_GT(img.count([](int, int, const auto& p) { return near_color(p, kRightColor); }), 100);
}

TEST(Footprints, TopViewPutsLeftFootAboveRight) {
  // Top view: +z to the right, +x (character's left) up. Left foot at x=+0.15.
  Scene s;
  s.footprints.push_back({Vec3(0.15, 0, 0), 0.0, true});
  s.footprints.push_back({Vec3(-0.15, 0, 0.4), 0.0, false});
  const Camera cam = camera(View::Top, 300, 300);
  const auto file = out("footprints.png");
  render_scene(s, cam, file);
  Image img(file);
  ASSERT_TRUE(img.ok());
  double ly = 0, ry = 0, lx = 0, rx = 0;
  int ln = 0, rn = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) {
      const auto p = img.at(x, y);
      if (near_color(p, kLeftColor, 0.1)) ly += y, lx += x, ++ln;
      if (near_color(p, kRightColor, 0.1)) ry += y, rx += x, ++rn;
    }
  ASSERT_GT(ln, 20);
  ASSERT_GT(rn, 20);
  EXPECT_LT(ly / ln, ry / rn);  // left foot higher in the picture
  EXPECT_LT(lx / ln, rx / rn);  // right foot further forward (+z = right)
}

TEST(RenderScene, TrackedDevicesAreMarkersNotBones) {
  // A headset and two controllers (the accentuation video's input): no bone
  // from the head to a hand in the side colours, a marker at each hand.
  Skeleton s;
  s.add_joint("Head", -1, Vec3(0, 1.6, 0));
  s.add_joint("LeftHand", 0, Vec3(0.3, -0.6, 0));
  s.add_joint("RightHand", 0, Vec3(-0.3, -0.6, 0));
  s.end_sites = {Vec3(0, 0.12, 0), Vec3(0, 0, 0.08), Vec3(0, 0, 0.08)};
  s.has_end_site = {1, 1, 1};
  resolve_roles(s);
  Scene scene;
  scene.figures.push_back(make_figure(s, Pose(s)));
  const Camera cam = camera(View::Front, 300, 300);
  const Image img = rendered(scene, cam, "devices.png");
  ASSERT_TRUE(img.ok());
  const Framing fr = frame_scene(scene, cam);
  const auto& p = scene.figures[0].positions;
  for (int hand : {1, 2}) {
    const Rgb side = hand == 1 ? kLeftColor : kRightColor;
    const auto at = fr.to_pixel(p[static_cast<std::size_t>(hand)]);
    EXPECT_TRUE(near_color(img.at(static_cast<int>(at.x()), static_cast<int>(at.y())), side)) << "no marker at hand " << hand;
    const auto mid = fr.to_pixel((p[0] + p[static_cast<std::size_t>(hand)]) / 2);
    int coloured = 0;
    for (int dx = -3; dx <= 3; ++dx)
      coloured += near_color(img.at(static_cast<int>(mid.x()) + dx, static_cast<int>(mid.y())), side, 0.15);
    EXPECT_EQ(coloured, 0) << "a side-coloured bone between the head and hand " << hand;
  }
}

TEST(RenderScene, TracedPathsNeverUseTheSideColours) {
  // The convention: left blue, right orange, paths green. A left joint's arc
  // was drawn orange (the default curve colour) in the walk-cycle arcs.
  Scene s;
  Curve c;
  for (int i = 0; i <= 20; ++i) c.points.emplace_back(0.3 * std::cos(i * 0.3), 1 + 0.3 * std::sin(i * 0.3), 0);
  c.marks = {0, 10};
  c.mark_labels = {"C", "P"};
  c.label = "LeftHand";
  s.curves.push_back(c);
  const Image img = rendered(s, camera(View::Front, 300, 300), "trace_colour.png");
  ASSERT_TRUE(img.ok());
  EXPECT_GT(img.count([](int, int, const auto& px) { return near_color(px, kTraceColor); }), 100);
  EXPECT_EQ(img.count([](int, int, const auto& px) { return near_color(px, kRightColor, 0.15); }), 0);
  EXPECT_EQ(img.count([](int, int, const auto& px) { return near_color(px, kLeftColor, 0.15); }), 0);
}

TEST(DrawCurves, ASegmentDarkensItsPixelsAndNothingFarFromIt) {
  const Vec3 a(-0.6, 0.5, 0), b(0.6, 1.4, 0);
  const Scene s = ink_curve({a, b});
  const Curve& c = s.curves[0];
  const Camera cam = camera(View::Front, 320, 320);
  const Image img = rendered(s, cam, "draw_segment.png");
  ASSERT_TRUE(img.ok());
  const Framing fr = frame_scene(s, cam);
  const Eigen::Vector2d pa = fr.to_pixel(a), pb = fr.to_pixel(b);
  const Eigen::Vector2d normal = Eigen::Vector2d(-(pb - pa).y(), (pb - pa).x()).normalized();
  for (double t = 0.2; t <= 0.8; t += 0.1) {
    const Eigen::Vector2d q = pa + t * (pb - pa);
    EXPECT_TRUE(near_color(pixel(img, q), c.color, 0.15)) << "on the segment at t = " << t;
    EXPECT_TRUE(is_background(pixel(img, q + 12 * normal))) << "12 px to one side at t = " << t;
    EXPECT_TRUE(is_background(pixel(img, q - 12 * normal))) << "12 px to the other side at t = " << t;
  }
  // Beyond the ends (round caps are only width/2 long) the picture stays white.
  EXPECT_TRUE(is_background(pixel(img, pb + 12 * (pb - pa).normalized())));
}

TEST(DrawCurves, NonFinitePointsLiftThePen) {
  const Vec3 a0(-0.6, 1, 0), a1(-0.3, 1, 0), b0(0.3, 1, 0), b1(0.6, 1, 0);
  const Scene s = ink_curve({a0, a1, Vec3::Constant(std::nan("")), b0, b1});
  const Curve& c = s.curves[0];
  const Camera cam = camera(View::Front, 320, 200);
  const Image img = rendered(s, cam, "draw_gap.png");
  ASSERT_TRUE(img.ok());
  const Framing fr = frame_scene(s, cam);
  EXPECT_TRUE(near_color(pixel(img, fr.to_pixel((a0 + a1) / 2)), c.color, 0.15));
  EXPECT_TRUE(near_color(pixel(img, fr.to_pixel((b0 + b1) / 2)), c.color, 0.15));
  EXPECT_TRUE(is_background(pixel(img, fr.to_pixel(Vec3(0, 1, 0)))));  // no line across the gap
}

TEST(DrawFigures, BonesInTheirSideColoursAndTranslucentFiguresArePaler) {
  const Skeleton& skel = walk_07_01().skeleton;
  const Pose rest(skel);
  Scene s;
  s.floor = false;
  s.figures.push_back(make_figure(skel, rest));
  const Camera cam = camera(View::Front, 400, 400);
  const Image opaque = rendered(s, cam, "draw_bones.png");
  s.figures[0].alpha = 0.3;
  const Image faint = rendered(s, cam, "draw_bones_faint.png");
  ASSERT_TRUE(opaque.ok());
  ASSERT_TRUE(faint.ok());
  const Framing fr = frame_scene(s, cam);
  const auto& p = s.figures[0].positions;
  auto mid = [&](const char* child) {
    const int j = skel.require(child);
    return fr.to_pixel((p[static_cast<std::size_t>(j)] + p[static_cast<std::size_t>(skel.parents[static_cast<std::size_t>(j)])]) / 2);
  };
  // Thigh bones: the left one bluish (blue above red), the right one orange (red above blue).
  const Rgba left = pixel(opaque, mid("LeftLeg")), right = pixel(opaque, mid("RightLeg"));
  EXPECT_GT(left.b, left.r + 0.2);
  EXPECT_GT(right.r, right.b + 0.2);
  // alpha 0.3 over white: each channel moves to 1 - 0.3 (1 - c).
  const Rgba lf = pixel(faint, mid("LeftLeg"));
  EXPECT_NEAR(lf.r, 1 - 0.3 * (1 - left.r), 0.03);
  EXPECT_NEAR(lf.b, 1 - 0.3 * (1 - left.b), 0.03);
  // Between the legs, below the pelvis, nothing is drawn.
  const int lk = skel.require("LeftLeg"), rk = skel.require("RightLeg");
  EXPECT_TRUE(is_background(pixel(opaque, fr.to_pixel((p[static_cast<std::size_t>(lk)] + p[static_cast<std::size_t>(rk)]) / 2))));
}

TEST(DrawFloor, SideViewFloorLineRunsAcrossThePanelAtHeightZero) {
  Scene s;
  Curve c;
  c.points = {Vec3(0, 0.8, -0.2), Vec3(0, 1.6, 0.2)};
  s.curves.push_back(c);
  const Camera cam = camera(View::Side, 400, 300);
  const Image img = rendered(s, cam, "draw_floor.png");
  ASSERT_TRUE(img.ok());
  const double y = frame_scene(s, cam).to_pixel(Vec3::Zero()).y();
  auto darkest_near = [&](int x, double yy) {
    double d = 1;
    for (int dy = -1; dy <= 1; ++dy) d = std::min(d, brightness(img.at(x, static_cast<int>(yy) + dy)));
    return d;
  };
  for (int x : {3, 100, 200, 396}) EXPECT_LT(darkest_near(x, y), 0.85) << "floor at x = " << x;
  // Half way between the floor and the content there is nothing.
  const double above = frame_scene(s, cam).to_pixel(Vec3(0, 0.4, 0)).y();
  EXPECT_GT(darkest_near(3, above), 0.97);
  // Without the floor, the panel's left edge column is blank.
  s.floor = false;
  const Image none = rendered(s, cam, "draw_no_floor.png");
  EXPECT_EQ(none.count([](int x, int, const Rgba& px) { return x == 3 && !is_background(px); }), 0);
}

TEST(Footprints, OutlineIsASoleAlongTheHeadingMirroredForTheRightFoot) {
  const Footprint left{Vec3(0.5, 0, 1.0), 0.0, true}, right{Vec3(0.5, 0, 1.0), 0.0, false};
  const auto l = detail::footprint_outline(left), r = detail::footprint_outline(right);
  ASSERT_EQ(l.size(), r.size());
  double zmin = 1e9, zmax = -1e9;
  for (std::size_t i = 0; i < l.size(); ++i) {
    EXPECT_EQ(l[i].y(), 0.0);  // on the floor
    EXPECT_NEAR(l[i].x() - 0.5, -(r[i].x() - 0.5), 1e-12);  // mirror images across the foot's axis
    EXPECT_EQ(l[i].z(), r[i].z());
    zmin = std::min(zmin, l[i].z()), zmax = std::max(zmax, l[i].z());
  }
  EXPECT_NEAR(zmax - zmin, 0.27, 0.02);  // ~0.26 m long along +z at heading 0
  // Turned a quarter about +y, the sole runs along +x instead: rotation of the same outline.
  const auto turned = detail::footprint_outline({Vec3(0.5, 0, 1.0), kPi / 2, true});
  const Quat q(Eigen::AngleAxisd(kPi / 2, Vec3::UnitY()));
  for (std::size_t i = 0; i < l.size(); ++i)
    EXPECT_LT((turned[i] - (Vec3(0.5, 0, 1.0) + q * (l[i] - Vec3(0.5, 0, 1.0)))).norm(), 1e-12);
}

// Uneven ground (walk cycles on stairs): the strip's treads and risers are
// drawn where the framing puts them, and nothing where there is no ground.
TEST(Ground, StairsAreDrawnFromTheSideAndFromAbove) {
  Scene s;
  s.floor = false;
  s.ground.profile = {Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 0.3, 1.01), Vec3(0, 0.3, 2)};
  s.ground.across = Vec3::UnitX();
  s.ground.half_width = 0.45;
  for (View v : {View::Side, View::Top}) {
    const Camera cam = camera(v, 400, 300);
    const auto file = out(std::string("ground_") + view_name(v) + ".png");
    render_scene(s, cam, file);
    Image img(file);
    ASSERT_TRUE(img.ok());
    const Framing fr = frame_scene(s, cam);
    auto inked = [&](const Vec3& p) {  // any pixel within 1 px of p's projection is not background
      const Eigen::Vector2d q = fr.to_pixel(p);
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          if (!is_background(img.at(static_cast<int>(q.x()) + dx, static_cast<int>(q.y()) + dy))) return true;
      return false;
    };
    if (v == View::Side) {
      EXPECT_TRUE(inked(Vec3(0, 0.3, 1.5)));    // the tread
      EXPECT_TRUE(inked(Vec3(0, 0.15, 1.005)));  // the riser
      EXPECT_TRUE(inked(Vec3(0, 0, 0.5)));      // the floor before the stairs
      EXPECT_FALSE(inked(Vec3(0, 0.15, 0.5)));  // air under the tread's height before the riser
    } else {
      EXPECT_TRUE(inked(Vec3(0.2, 0.3, 1.5)));   // on the strip
      EXPECT_FALSE(inked(Vec3(0.8, 0.3, 1.5)));  // beside it
    }
  }
}
