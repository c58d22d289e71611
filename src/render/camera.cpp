// Views, projection, framing and figure construction.
#include "scene_draw.hpp"

#include <legwork/core/fk.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace legwork::render {

View parse_view(const std::string& name) {
  if (name == "side") return View::Side;
  if (name == "front") return View::Front;
  if (name == "three-quarter" || name == "threequarter" || name == "3q") return View::ThreeQuarter;
  if (name == "top") return View::Top;
  throw Error("unknown view '" + name + "' (expected side, front, three-quarter or top)");
}

std::string view_name(View v) {
  switch (v) {
    case View::Side: return "side";
    case View::Front: return "front";
    case View::ThreeQuarter: return "three-quarter";
    case View::Top: return "top";
  }
  return "side";
}

ViewBasis view_basis(View v) {
  switch (v) {
    case View::Side: return {Vec3::UnitZ(), Vec3::UnitY(), -Vec3::UnitX()};
    case View::Front: return {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
    case View::Top: return {Vec3::UnitZ(), Vec3::UnitX(), Vec3::UnitY()};
    case View::ThreeQuarter: {
      // Halfway between Side (right = +z) and Front (right = +x), then tilted
      // so the camera looks 20 degrees down onto the floor.
      const double tilt = deg2rad(20.0);
      const Vec3 right = Vec3(1, 0, 1).normalized();
      const Vec3 level_toward = Vec3(-1, 0, 1).normalized();  // camera in front-right
      const Vec3 toward = (std::cos(tilt) * level_toward + std::sin(tilt) * Vec3::UnitY()).normalized();
      const Vec3 up = toward.cross(right).normalized();
      return {right, up, toward};
    }
  }
  return {Vec3::UnitZ(), Vec3::UnitY(), -Vec3::UnitX()};
}

Eigen::Vector2d project(View v, const Vec3& p) {
  const ViewBasis b = view_basis(v);
  return {p.dot(b.right), p.dot(b.up)};
}

Eigen::Vector2d Framing::to_pixel(const Vec3& p) const {
  const Eigen::Vector2d q = project(view, p) - centre_plane;
  return {centre_pixel.x() + q.x() / metres_per_pixel, centre_pixel.y() - q.y() / metres_per_pixel};
}

std::vector<Side> joint_sides(const Skeleton& skel) {
  const int n = skel.joint_count();
  std::vector<Side> side(static_cast<std::size_t>(n), Side::Centre);
  // Roles first: a joint below a sided role joint takes that side.
  struct Root {
    Role role;
    Side side;
  };
  const Root roots[] = {{Role::LeftHip, Side::Left},         {Role::LeftClavicle, Side::Left},
                        {Role::LeftShoulder, Side::Left},    {Role::RightHip, Side::Right},
                        {Role::RightClavicle, Side::Right},  {Role::RightShoulder, Side::Right}};
  // One pass (parents precede children): a role joint takes its side, any
  // other joint its parent's (linear, not joints x depth).
  std::vector<unsigned char> is_root(static_cast<std::size_t>(n), 0);
  for (const auto& r : roots) {
    const int rj = skel.roles[r.role];
    if (rj >= 0 && !is_root[static_cast<std::size_t>(rj)]) {
      is_root[static_cast<std::size_t>(rj)] = 1;
      side[static_cast<std::size_t>(rj)] = r.side;
    }
  }
  for (int j = 0; j < n; ++j) {
    const int parent = skel.parents[static_cast<std::size_t>(j)];
    if (!is_root[static_cast<std::size_t>(j)] && parent >= 0 && parent < j)
      side[static_cast<std::size_t>(j)] = side[static_cast<std::size_t>(parent)];
  }
  // Mirror pairs no role covered (e.g. extra helper joints): the one further
  // to +x in the rest pose is the left one (+x = the character's left).
  if (static_cast<int>(skel.mirror.size()) == n && n > 0) {
    const auto rest = joint_positions(skel, Pose(skel));
    for (int j = 0; j < n; ++j) {
      const auto ju = static_cast<std::size_t>(j);
      const int m = skel.mirror[ju];
      if (side[ju] != Side::Centre || m == j || m < 0 || m >= n) continue;
      const double dx = rest[ju].x() - rest[static_cast<std::size_t>(m)].x();
      if (std::abs(dx) > 1e-6) side[ju] = dx > 0 ? Side::Left : Side::Right;
    }
  }
  return side;
}

Figure make_figure(const Skeleton& skel, ConstPoseRef pose, double alpha, std::string label) {
  const auto n = static_cast<std::size_t>(skel.joint_count());
  std::vector<Transform> model(n);
  forward_kinematics(skel, pose, model);
  Figure f;
  f.skeleton = &skel;
  f.alpha = alpha;
  f.label = std::move(label);
  f.positions.resize(n);
  for (std::size_t j = 0; j < n; ++j) f.positions[j] = model[j].translation;
  if (skel.has_end_site.size() == n) {
    f.end_sites.resize(n);
    for (std::size_t j = 0; j < n; ++j) f.end_sites[j] = end_site_position(skel, model, static_cast<int>(j));
  }
  return f;
}

namespace detail {

// Points a scene draws, for framing: joints, tips, curve points, footprint corners.
void for_each_content_point(const Scene& scene, const std::function<void(const Vec3&)>& fn) {
  for (const auto& f : scene.figures) {
    for (const auto& p : f.positions) fn(p);
    if (f.skeleton && f.end_sites.size() == f.positions.size())
      for (std::size_t j = 0; j < f.end_sites.size(); ++j)
        if (j < f.skeleton->has_end_site.size() && f.skeleton->has_end_site[j]) fn(f.end_sites[j]);
  }
  for (const auto& c : scene.curves)
    for (const auto& p : c.points) fn(p);
  for (const auto& fp : scene.footprints)
    for (const auto& p : footprint_outline(fp)) fn(p);
  for (const auto& p : scene.ground.profile) fn(p);
}

Layout layout_of(const Scene& scene) {
  Layout l;
  l.top = scene.title.empty() ? 0 : 26;
  bool labels = false;
  for (const auto& f : scene.figures) labels = labels || !f.label.empty();
  l.bottom = labels ? 20 : 0;
  return l;
}

}  // namespace detail

namespace detail {

bool plane_bounds(const Scene& scene, View view, Eigen::Vector2d& lo, Eigen::Vector2d& hi) {
  lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  hi = -lo;
  // Content plus its shadow on the floor, so the floor line is in the picture.
  const bool floor = scene.floor && view != View::Top;
  for_each_content_point(scene, [&](const Vec3& p) {
    if (!p.allFinite()) return;
    const Eigen::Vector2d q = project(view, p);
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
    if (floor) {
      const Eigen::Vector2d f = project(view, Vec3(p.x(), 0.0, p.z()));
      lo = lo.cwiseMin(f);
      hi = hi.cwiseMax(f);
    }
  });
  return lo.x() <= hi.x();
}

}  // namespace detail

Framing frame_scene(const Scene& scene, const Camera& cam) {
  using detail::Layout;
  if (cam.width <= 0 || cam.height <= 0)
    throw Error("camera size " + std::to_string(cam.width) + "x" + std::to_string(cam.height) + " must be positive");
  Framing fr;
  fr.view = cam.view;
  fr.width = cam.width;
  fr.height = cam.height;

  Eigen::Vector2d lo, hi;
  bool any = false;
  if (cam.fixed_bounds) {
    lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
    hi = -lo;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector2d q = project(cam.view, Vec3(c & 1 ? cam.bounds_max.x() : cam.bounds_min.x(),
                                                       c & 2 ? cam.bounds_max.y() : cam.bounds_min.y(),
                                                       c & 4 ? cam.bounds_max.z() : cam.bounds_min.z()));
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    any = lo.allFinite() && hi.allFinite();
  } else {
    any = detail::plane_bounds(scene, cam.view, lo, hi);
  }
  if (!any) {  // nothing to draw: a 2 m square around the origin
    lo = Eigen::Vector2d(-1, -1);
    hi = Eigen::Vector2d(1, 1);
  }
  // Never zoom in beyond 0.5 m across (a single point stays readable).
  const Eigen::Vector2d mid = (lo + hi) / 2;
  const Eigen::Vector2d half = ((hi - lo) / 2).cwiseMax(0.25);

  const Layout l = detail::layout_of(scene);
  const double mx = cam.margin * cam.width, my = cam.margin * cam.height;
  const double avail_w = std::max(8.0, cam.width - 2 * mx);
  const double avail_h = std::max(8.0, cam.height - 2 * my - l.top - l.bottom);
  fr.metres_per_pixel = cam.metres_per_pixel > 0 ? cam.metres_per_pixel
                                                 : std::max(2 * half.x() / avail_w, 2 * half.y() / avail_h);
  fr.centre_plane = mid;
  fr.centre_pixel = Eigen::Vector2d(cam.width / 2.0, my + l.top + avail_h / 2);
  return fr;
}

}  // namespace legwork::render
