// Cameras: view bases and projection, framing (fit, fixed bounds, fixed
// scale), figures by FK and which side of the body each joint is on.
#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/render/render.hpp>

#include "render_test_util.hpp"
#include "testdata.hpp"
#include "error_message.hpp"

using namespace legwork;
using namespace legwork::render;
using legwork::render::testing::camera;
using legwork::render::testing::Image;
using legwork::render::testing::near_color;
using legwork::render::testing::out;
using legwork::render::testing::walk_07_01;
using legwork::render::testing::out_dir;

using legwork::testdata::message_of;

namespace {

// A scene holding one curve through `points` (framing only looks at content points).
Scene curve_scene(std::vector<Vec3> points, bool floor = false) {
  Scene s;
  s.floor = floor;
  Curve c;
  c.points = std::move(points);
  s.curves.push_back(c);
  return s;
}

}  // namespace

TEST(Projection, EachViewMapsAKnownPoint) {
  const Vec3 p(1.0, 2.0, 3.0);  // x = character's left, y = up, z = forward
  EXPECT_TRUE(project(View::Side, p).isApprox(Eigen::Vector2d(3.0, 2.0)));   // forward to the right
  EXPECT_TRUE(project(View::Front, p).isApprox(Eigen::Vector2d(1.0, 2.0)));  // left to the right
  EXPECT_TRUE(project(View::Top, p).isApprox(Eigen::Vector2d(3.0, 1.0)));    // forward right, left up
  // Three-quarter: right = (x + z)/sqrt2, up mostly +y with the camera looking down.
  const auto q = project(View::ThreeQuarter, p);
  EXPECT_NEAR(q.x(), 4.0 / std::sqrt(2.0), 1e-12);
  const auto b = view_basis(View::ThreeQuarter);
  EXPECT_NEAR(b.right.norm(), 1, 1e-12);
  EXPECT_NEAR(b.up.dot(b.right), 0, 1e-12);
  EXPECT_NEAR(b.toward.dot(b.up), 0, 1e-12);
  EXPECT_GT(b.up.y(), 0.9);
  EXPECT_GT(b.toward.y(), 0.2);  // camera above the floor, looking down
  EXPECT_GT(b.toward.z(), 0.5);  // in front of the character
  // Every basis is right-handed: right x up = towards the viewer.
  for (View v : {View::Side, View::Front, View::ThreeQuarter, View::Top}) {
    const auto bb = view_basis(v);
    EXPECT_TRUE(bb.right.cross(bb.up).isApprox(bb.toward)) << view_name(v);
    EXPECT_EQ(parse_view(view_name(v)), v);
  }
  EXPECT_THROW(parse_view("diagonal"), Error);
}

TEST(Projection, PixelsMatchTheDrawing) {
  // A marked dot at a known 3D point lands on the pixel Framing::to_pixel gives,
  // in every view; and equal metres are equal pixels on both axes.
  const Vec3 p(0.4, 1.1, -0.3);
  for (View v : {View::Side, View::Front, View::ThreeQuarter, View::Top}) {
    Scene s;
    s.floor = false;
    Curve c;
    c.points = {Vec3(-1, 0, -1), p, Vec3(1, 2, 1)};
    c.color = {0.0, 0.6, 0.0};
    c.width = 3;
    c.marks = {1};
    s.curves.push_back(c);
    const Camera cam = camera(v, 300, 200);
    const auto file = out("proj_" + view_name(v) + ".png");
    render_scene(s, cam, file);
    const Framing fr = frame_scene(s, cam);
    const auto px = fr.to_pixel(p);
    Image img(file);
    ASSERT_TRUE(img.ok());
    const auto got = img.at(static_cast<int>(px.x()), static_cast<int>(px.y()));
    EXPECT_TRUE(near_color(got, c.color, 0.1)) << view_name(v) << " at " << px.transpose();
    // A 1 m step along the view's right and up axes is the same number of pixels.
    const auto b = view_basis(v);
    const double sx = (fr.to_pixel(p + b.right) - px).norm(), sy = (fr.to_pixel(p + b.up) - px).norm();
    EXPECT_NEAR(sx, sy, 1e-9);
    EXPECT_LT(fr.to_pixel(p + b.up).y(), px.y());  // up is up in the picture
  }
}

TEST(Sides, CmuSkeletonLegsAndArmsAreSided) {
  const auto& skel = walk_07_01().skeleton;
  const auto sides = joint_sides(skel);
  EXPECT_EQ(sides[static_cast<std::size_t>(skel.require("LeftFoot"))], Side::Left);
  EXPECT_EQ(sides[static_cast<std::size_t>(skel.require("LeftHand"))], Side::Left);
  EXPECT_EQ(sides[static_cast<std::size_t>(skel.require("RightToeBase"))], Side::Right);
  EXPECT_EQ(sides[static_cast<std::size_t>(skel.require("RightForeArm"))], Side::Right);
  EXPECT_EQ(sides[static_cast<std::size_t>(skel.require("Head"))], Side::Centre);
  EXPECT_EQ(sides[static_cast<std::size_t>(skel.require("Hips"))], Side::Centre);
}

TEST(Projection, ViewNamesAndAliases) {
  EXPECT_EQ(parse_view("3q"), View::ThreeQuarter);
  EXPECT_EQ(parse_view("threequarter"), View::ThreeQuarter);
  EXPECT_EQ(message_of([] { parse_view("diagonal"); }),
            "unknown view 'diagonal' (expected side, front, three-quarter or top)");
}

TEST(Framing, ContentCentreLandsOnThePanelCentreAndFitsTheMargin) {
  // A 2 m x 1 m box in the front view (x right, y up), well above the floor.
  const Scene s = curve_scene({Vec3(-1, 1, 0), Vec3(1, 2, 0)});
  Camera cam = camera(View::Front, 400, 300);
  cam.margin = 0.1;
  const Framing fr = frame_scene(s, cam);
  EXPECT_EQ(fr.view, View::Front);
  EXPECT_EQ(fr.width, 400);
  EXPECT_EQ(fr.height, 300);
  // No title or labels: the content's centre is the picture's centre.
  const auto c = fr.to_pixel(Vec3(0, 1.5, 0));
  EXPECT_NEAR(c.x(), 200, 1e-9);
  EXPECT_NEAR(c.y(), 150, 1e-9);
  // The limiting axis is the width: 2 m over 400 - 2 * 40 pixels.
  EXPECT_NEAR(fr.metres_per_pixel, 2.0 / 320, 1e-12);
  EXPECT_NEAR(fr.to_pixel(Vec3(-1, 1.5, 0)).x(), 40, 1e-9);
  EXPECT_NEAR(fr.to_pixel(Vec3(1, 1.5, 0)).x(), 360, 1e-9);
  // Depth (z) does not move a point in the front view; y grows downwards in pixels.
  EXPECT_TRUE(fr.to_pixel(Vec3(0.3, 1.2, 5)).isApprox(fr.to_pixel(Vec3(0.3, 1.2, -5))));
  EXPECT_GT(fr.to_pixel(Vec3(0, 1, 0)).y(), c.y());
}

TEST(Framing, FloorShadowAndTitleAreKeptInThePicture) {
  // With the floor on, the content's shadow at y = 0 must be inside the picture too.
  const Scene s = curve_scene({Vec3(0, 1.5, -0.5), Vec3(0, 2, 0.5)}, true);
  const Framing fr = frame_scene(s, camera(View::Side, 300, 300));
  const double floor_y = fr.to_pixel(Vec3(0, 0, 0)).y();
  EXPECT_LT(floor_y, 300);
  EXPECT_GT(fr.to_pixel(Vec3(0, 2, 0)).y(), 0);
  // A title takes room at the top: the content moves down.
  Scene titled = s;
  titled.title = "t";
  const Framing ft = frame_scene(titled, camera(View::Side, 300, 300));
  EXPECT_GT(ft.to_pixel(Vec3(0, 2, 0)).y(), fr.to_pixel(Vec3(0, 2, 0)).y());
}

TEST(Framing, FixedBoundsAndFixedScale) {
  Camera cam = camera(View::Side, 500, 250);
  cam.margin = 0;
  cam.fixed_bounds = true;
  cam.bounds_min = Vec3(-3, 0, -1);
  cam.bounds_max = Vec3(3, 1, 3);
  // The content is ignored: the box's centre (z = 1, y = 0.5) is the picture's centre.
  const Framing fr = frame_scene(curve_scene({Vec3(0, 50, 70)}), cam);
  EXPECT_TRUE(fr.to_pixel(Vec3(0, 0.5, 1)).isApprox(Eigen::Vector2d(250, 125)));
  // 4 m of z over 500 pixels vs 1 m of y over 250: the width limits.
  EXPECT_NEAR(fr.metres_per_pixel, 4.0 / 500, 1e-12);
  cam.metres_per_pixel = 0.01;
  const Framing fixed = frame_scene(curve_scene({Vec3(0, 50, 70)}), cam);
  EXPECT_EQ(fixed.metres_per_pixel, 0.01);
  EXPECT_NEAR((fixed.to_pixel(Vec3(0, 0.5, 2)) - fixed.to_pixel(Vec3(0, 0.5, 1))).x(), 100, 1e-9);
}

TEST(Framing, EmptyScenesAndTinyContent) {
  // Nothing to draw: a 2 m square around the origin.
  Camera cam = camera(View::Front, 200, 200);
  cam.margin = 0;
  const Framing empty = frame_scene(Scene{}, cam);
  EXPECT_TRUE(empty.to_pixel(Vec3::Zero()).isApprox(Eigen::Vector2d(100, 100)));
  EXPECT_NEAR(empty.metres_per_pixel, 2.0 / 200, 1e-12);
  // A single point is never zoomed in beyond 0.5 m across.
  const Framing one = frame_scene(curve_scene({Vec3(0.2, 1, 0)}), cam);
  EXPECT_NEAR(one.metres_per_pixel, 0.5 / 200, 1e-12);
  EXPECT_TRUE(one.to_pixel(Vec3(0.2, 1, 0)).isApprox(Eigen::Vector2d(100, 100)));
  // Non-finite points do not take part in the framing.
  const Framing nan = frame_scene(curve_scene({Vec3(0.2, 1, 0), Vec3::Constant(std::nan(""))}), cam);
  EXPECT_EQ(nan.metres_per_pixel, one.metres_per_pixel);
  EXPECT_EQ(message_of([] { frame_scene(Scene{}, camera(View::Side, 0, 480)); }), "camera size 0x480 must be positive");
}

TEST(Figures, PositionsAndTipsAreTheForwardKinematics) {
  const Motion& m = walk_07_01();
  const Figure f = make_figure(m.skeleton, m.frame(30), 0.4, "thirty");
  EXPECT_EQ(f.skeleton, &m.skeleton);
  EXPECT_EQ(f.alpha, 0.4);
  EXPECT_EQ(f.label, "thirty");
  const auto want = joint_positions(m.skeleton, m.frame(30));
  ASSERT_EQ(f.positions.size(), want.size());
  for (std::size_t j = 0; j < want.size(); ++j) EXPECT_LT((f.positions[j] - want[j]).norm(), 1e-12);
  // An End Site tip sits its rest offset away from its joint (a rigid bone).
  ASSERT_EQ(f.end_sites.size(), want.size());
  const int head = m.skeleton.roles[Role::Head];
  ASSERT_TRUE(m.skeleton.has_end_site[static_cast<std::size_t>(head)]);
  EXPECT_NEAR((f.end_sites[static_cast<std::size_t>(head)] - f.positions[static_cast<std::size_t>(head)]).norm(),
              m.skeleton.end_sites[static_cast<std::size_t>(head)].norm(), 1e-9);
}

TEST(Sides, MirrorPairsDecideWhereNoRoleDoes) {
  // Two arms without any role names: the joint at +x (the character's left) is Left.
  Skeleton s;
  s.add_joint("root", -1, Vec3(0, 1, 0));
  s.add_joint("a", 0, Vec3(0.3, 0, 0));
  s.add_joint("b", 0, Vec3(-0.3, 0, 0));
  s.add_joint("a_tip", 1, Vec3(0.2, 0, 0));
  s.add_joint("b_tip", 2, Vec3(-0.2, 0, 0));
  s.mirror = {0, 2, 1, 4, 3};
  EXPECT_EQ(joint_sides(s), (std::vector<Side>{Side::Centre, Side::Left, Side::Right, Side::Left, Side::Right}));
  s.mirror.clear();  // no mirror data: everything is centre
  EXPECT_EQ(joint_sides(s), std::vector<Side>(5, Side::Centre));
}
