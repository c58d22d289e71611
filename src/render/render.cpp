// Pictures: one scene, panel grids, contact sheets, trajectories.
#include "scene_draw.hpp"

#include <legwork/core/fk.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::render {

namespace {
// Widest multi-view sheet drawn (pixels); wider content is scaled into it by the camera fit.
constexpr double kMaxSheetWidth = 16384;
}  // namespace

using detail::Align;
using detail::Canvas;

void render_scene(const Scene& scene, const Camera& cam, const std::string& path) {
  detail::format_of(path);  // bad extension before any work
  const Framing fr = frame_scene(scene, cam);
  Canvas canvas(path, cam.width, cam.height);
  detail::draw_scene(canvas.cr(), scene, fr);
  canvas.finish();
}

void render_panels(const std::vector<Panel>& panels, int cols, const std::string& path, const std::string& title) {
  detail::format_of(path);
  if (panels.empty()) throw Error("render_panels('" + path + "'): no panels to draw");
  if (cols < 1) throw Error("render_panels('" + path + "'): cols must be >= 1");
  const int n = static_cast<int>(panels.size());
  const int rows = (n + cols - 1) / cols;
  // Each column is as wide as its widest panel, each row as tall as its tallest.
  std::vector<int> col_w(static_cast<std::size_t>(cols), 0), row_h(static_cast<std::size_t>(rows), 0);
  for (int i = 0; i < n; ++i) {
    const auto& c = panels[static_cast<std::size_t>(i)].camera;
    auto& w = col_w[static_cast<std::size_t>(i % cols)];
    auto& h = row_h[static_cast<std::size_t>(i / cols)];
    w = std::max(w, c.width);
    h = std::max(h, c.height);
  }
  const int title_h = title.empty() ? 0 : 34;
  int width = 0, height = title_h;
  for (int w : col_w) width += w;
  for (int h : row_h) height += h;
  Canvas canvas(path, width, height);
  cairo_t* cr = canvas.cr();
  if (!title.empty()) detail::title(cr, 10, 24, title, 17, width - 20);
  int y = title_h;
  for (int r = 0; r < rows; ++r) {
    int x = 0;
    for (int c = 0; c < cols && r * cols + c < n; ++c) {
      const Panel& p = panels[static_cast<std::size_t>(r * cols + c)];
      const Framing fr = frame_scene(p.scene, p.camera);
      // Centre a smaller panel in its cell.
      const double ox = x + (col_w[static_cast<std::size_t>(c)] - p.camera.width) / 2.0;
      const double oy = y + (row_h[static_cast<std::size_t>(r)] - p.camera.height) / 2.0;
      cairo_save(cr);
      cairo_translate(cr, ox, oy);
      detail::draw_scene(cr, p.scene, fr);
      cairo_restore(cr);
      // A hairline between panels.
      if (r > 0 || title_h > 0) {
        cairo_set_source_rgb(cr, 0.85, 0.85, 0.87);
        cairo_set_line_width(cr, 1);
        cairo_move_to(cr, x + 6, y + 0.5);
        cairo_line_to(cr, x + col_w[static_cast<std::size_t>(c)] - 6, y + 0.5);
        cairo_stroke(cr);
      }
      x += col_w[static_cast<std::size_t>(c)];
    }
    y += row_h[static_cast<std::size_t>(r)];
  }
  canvas.finish();
}

namespace {

// Heading (radians about +y, 0 = facing +z) of a figure from its hips:
// forward = left x up, with left = left hip - right hip.
bool figure_heading(const Skeleton& skel, const std::vector<Vec3>& pos, double& heading) {
  const int l = skel.roles[Role::LeftHip], r = skel.roles[Role::RightHip];
  if (l < 0 || r < 0) return false;
  const Vec3 left = pos[static_cast<std::size_t>(l)] - pos[static_cast<std::size_t>(r)];
  const Vec3 fwd = left.cross(Vec3::UnitY());
  if (std::hypot(fwd.x(), fwd.z()) < 1e-9) return false;
  heading = std::atan2(fwd.x(), fwd.z());
  return true;
}

void transform_figure(Figure& f, const Eigen::Matrix3d& rot, const Vec3& shift) {
  for (auto& p : f.positions) p = rot * p + shift;
  for (auto& p : f.end_sites) p = rot * p + shift;
}

}  // namespace

void render_contact_sheet(const Skeleton& skel, const std::vector<Pose>& poses, const SheetOptions& opt,
                          const std::string& path) {
  detail::format_of(path);
  if (poses.empty()) throw Error("contact sheet '" + path + "': no poses to draw");
  if (opt.views.empty()) throw Error("contact sheet '" + path + "': no views requested");
  for (const auto& p : poses)
    if (p.joint_count() != skel.joint_count())
      throw Error("contact sheet '" + path + "': a pose has " + std::to_string(p.joint_count()) +
                  " joints but the skeleton has " + std::to_string(skel.joint_count()));

  // Figures with the root's horizontal translation removed; optionally all
  // turned by one common angle so the mean heading faces +z (front = face).
  std::vector<Figure> base;
  double sx = 0, cz = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    base.push_back(make_figure(skel, poses[i], 1.0, i < opt.labels.size() ? opt.labels[i] : ""));
    double h = 0;
    if (figure_heading(skel, base.back().positions, h)) {
      sx += std::sin(h);
      cz += std::cos(h);
    }
  }
  const double turn = opt.face_forward && std::hypot(sx, cz) > 1e-9 ? -std::atan2(sx, cz) : 0.0;
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(turn, Vec3::UnitY()).toRotationMatrix();
  for (std::size_t i = 0; i < base.size(); ++i) {
    const Vec3 root = base[i].positions[0];
    transform_figure(base[i], rot, Vec3::Zero());
    const Vec3 r = rot * root;
    transform_figure(base[i], Eigen::Matrix3d::Identity(), Vec3(-r.x(), 0, -r.z()));
    if (opt.active >= 0) base[i].alpha = static_cast<int>(i) == opt.active ? 1.0 : opt.inactive_alpha;
  }

  // One scene per view, poses spread along the picture's horizontal axis.
  std::vector<Panel> panels;
  for (View v : opt.views) {
    Panel p;
    p.camera.view = v;
    p.camera.height = opt.panel_height;
    p.camera.margin = 0.06;
    Vec3 along = view_basis(v).right;
    along.y() = 0;
    along.normalize();
    for (std::size_t i = 0; i < base.size(); ++i) {
      Figure f = base[i];
      transform_figure(f, Eigen::Matrix3d::Identity(), along * (opt.spacing * static_cast<double>(i)));
      p.scene.figures.push_back(std::move(f));
    }
    p.scene.title = view_name(v) + " view";
    panels.push_back(std::move(p));
  }
  // One scale for every row (figures the same size in all views), and one width.
  double mpp = 0;
  for (auto& p : panels) {
    p.camera.width = 100000;  // height-limited fit
    mpp = std::max(mpp, frame_scene(p.scene, p.camera).metres_per_pixel);
  }
  int width = 0;
  for (auto& p : panels) {
    Eigen::Vector2d lo, hi;
    detail::plane_bounds(p.scene, p.camera.view, lo, hi);
    // In double first: a clip that wanders kilometres sideways must not overflow the int.
    const double w = std::ceil((hi.x() - lo.x()) / mpp / (1 - 2 * p.camera.margin)) + 20;
    width = std::max(width, static_cast<int>(std::clamp(std::isfinite(w) ? w : 0.0, 0.0, kMaxSheetWidth)));
  }
  width = std::max(width, 360);
  for (auto& p : panels) {
    p.camera.width = width;
    p.camera.metres_per_pixel = mpp;
  }
  render_panels(panels, 1, path, opt.title);
}

void render_trajectory(const Motion& m, int joint, const std::vector<int>& marked_frames, const Camera& cam,
                       const std::string& path) {
  render_trajectory(m, joint, marked_frames, cam, path, TrajectoryOptions{});
}

void render_trajectory(const Motion& m, int joint, const std::vector<int>& marked_frames, const Camera& cam,
                       const std::string& path, const TrajectoryOptions& opt) {
  detail::format_of(path);
  if (joint < 0 || joint >= m.joint_count())
    throw Error("trajectory '" + path + "': joint index " + std::to_string(joint) + " is outside 0.." +
                std::to_string(m.joint_count() - 1));
  if (m.frame_count() == 0) throw Error("trajectory '" + path + "': the motion has no frames");
  const int first = opt.first_frame, last = opt.last_frame < 0 ? m.frame_count() - 1 : opt.last_frame;
  if (first < 0 || last >= m.frame_count() || first > last)
    throw Error("trajectory '" + path + "': frames " + std::to_string(first) + ":" + std::to_string(last) +
                " are outside the motion's 0:" + std::to_string(m.frame_count() - 1));
  std::vector<int> marks = marked_frames;
  if (marks.empty()) {  // five evenly spaced frames
    const int n = std::min(5, last - first + 1);
    for (int i = 0; i < n; ++i) marks.push_back(first + (n > 1 ? i * (last - first) / (n - 1) : 0));
  }
  for (int f : marks)
    if (f < first || f > last)
      throw Error("trajectory '" + path + "': marked frame " + std::to_string(f) + " is outside frames " +
                  std::to_string(first) + ":" + std::to_string(last));

  Scene scene;
  const auto& name = m.skeleton.names[static_cast<std::size_t>(joint)];
  std::vector<Transform> model(static_cast<std::size_t>(m.joint_count()));
  Curve path_curve;
  path_curve.color = kTraceColor;
  path_curve.width = 2.0;
  for (int f = first; f <= last; ++f) {
    forward_kinematics(m.skeleton, m.frame(f), model);
    path_curve.points.push_back(model[static_cast<std::size_t>(joint)].translation);
  }
  for (int f : marks) {
    scene.figures.push_back(make_figure(m.skeleton, m.frame(f), 0.35));
    path_curve.marks.push_back(f - first);
    path_curve.mark_labels.push_back(std::to_string(f));
  }
  path_curve.label = name;
  scene.curves.push_back(std::move(path_curve));
  scene.footprints = opt.footprints;
  scene.title = !opt.title.empty() ? opt.title
                                   : name + " path over " + std::to_string(last - first + 1) + " frames (" +
                                         view_name(cam.view) + " view; dots = marked frames)";
  render_scene(scene, cam, path);
}

}  // namespace legwork::render
