// Drawing scenes: floor, footprints, curves, stick figures, text, scale bar.
#include "scene_draw.hpp"

#include <legwork/render/layout.hpp>

#include <algorithm>
#include <cmath>

namespace legwork::render::detail {

namespace {

constexpr Rgb kInk{0.12, 0.12, 0.14};
constexpr Rgb kFloor{0.55, 0.55, 0.58};
constexpr Rgb kGrid{0.88, 0.88, 0.9};

void move_to(cairo_t* cr, const Eigen::Vector2d& p) { cairo_move_to(cr, p.x(), p.y()); }
void line_to(cairo_t* cr, const Eigen::Vector2d& p) { cairo_line_to(cr, p.x(), p.y()); }

// Stroke width in pixels for bones: ~2 cm, but readable at any zoom.
double bone_width(const Framing& fr) { return std::clamp(0.022 / fr.metres_per_pixel, 1.6, 6.0); }

// Model-space box of the scene's content, for the floor grid.
bool content_box(const Scene& scene, Vec3& lo, Vec3& hi) {
  lo = Vec3::Constant(1e300);
  hi = Vec3::Constant(-1e300);
  bool any = false;
  for_each_content_point(scene, [&](const Vec3& p) {
    if (!p.allFinite()) return;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
    any = true;
  });
  return any;
}

void draw_floor(cairo_t* cr, const Scene& scene, const Framing& fr) {
  Vec3 lo, hi;
  const bool any = content_box(scene, lo, hi);
  cairo_save(cr);
  if (fr.view == View::Side || fr.view == View::Front) {
    // The floor seen edge-on: one line across the panel, ticks every metre.
    const double y = fr.to_pixel(Vec3::Zero()).y();
    set_color(cr, kFloor);
    cairo_set_line_width(cr, 1.2);
    cairo_move_to(cr, 0, y);
    cairo_line_to(cr, fr.width, y);
    cairo_stroke(cr);
    const Vec3 axis = view_basis(fr.view).right;
    const double u0 = project(fr.view, Vec3::Zero()).x();
    const double span_m = fr.width * fr.metres_per_pixel;
    const double step = span_m > 12 ? 5.0 : 1.0;
    const double left_u = fr.centre_plane.x() - fr.centre_pixel.x() * fr.metres_per_pixel;
    cairo_set_line_width(cr, 1.0);
    for (double u = std::ceil(left_u / step) * step; u <= left_u + span_m; u += step) {
      const double x = fr.to_pixel(axis * (u - u0)).x();
      cairo_move_to(cr, x, y);
      cairo_line_to(cr, x, y + 5);
    }
    cairo_stroke(cr);
  } else if (any) {
    // A floor grid (y = 0) under the content, lines every nice step.
    const double span = std::max(hi.x() - lo.x(), hi.z() - lo.z());
    const double step = std::max(0.25, nice_step(span + 1.0, 8));
    const double x0 = std::floor((lo.x() - 0.3) / step) * step, x1 = std::ceil((hi.x() + 0.3) / step) * step;
    const double z0 = std::floor((lo.z() - 0.3) / step) * step, z1 = std::ceil((hi.z() + 0.3) / step) * step;
    set_color(cr, kGrid);
    cairo_set_line_width(cr, 1.0);
    for (double x = x0; x <= x1 + 1e-9; x += step) {
      move_to(cr, fr.to_pixel(Vec3(x, 0, z0)));
      line_to(cr, fr.to_pixel(Vec3(x, 0, z1)));
    }
    for (double z = z0; z <= z1 + 1e-9; z += step) {
      move_to(cr, fr.to_pixel(Vec3(x0, 0, z)));
      line_to(cr, fr.to_pixel(Vec3(x1, 0, z)));
    }
    cairo_stroke(cr);
  }
  cairo_restore(cr);
}

// The ground strip: one quad per profile segment (light grey, treads and
// slopes; risers show as their edges), far edge first, then the near edge.
void draw_ground(cairo_t* cr, const Scene& scene, const Framing& fr) {
  const GroundStrip& g = scene.ground;
  if (g.profile.size() < 2) return;
  const Vec3 side = g.across.normalized() * g.half_width;
  cairo_save(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_width(cr, 1.0);
  for (std::size_t i = 0; i + 1 < g.profile.size(); ++i) {
    const Vec3 &a = g.profile[i], &b = g.profile[i + 1];
    move_to(cr, fr.to_pixel(a - side));
    line_to(cr, fr.to_pixel(b - side));
    line_to(cr, fr.to_pixel(b + side));
    line_to(cr, fr.to_pixel(a + side));
    cairo_close_path(cr);
  }
  cairo_set_source_rgba(cr, kGrid[0], kGrid[1], kGrid[2], 0.55);
  cairo_fill(cr);
  set_color(cr, kFloor);
  for (const Vec3& edge : {side, Vec3(-side)}) {
    move_to(cr, fr.to_pixel(g.profile.front() + edge));
    for (const Vec3& p : g.profile) line_to(cr, fr.to_pixel(p + edge));
    cairo_stroke(cr);
  }
  cairo_restore(cr);
}

void draw_footprints(cairo_t* cr, const Scene& scene, const Framing& fr) {
  cairo_save(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const auto& fp : scene.footprints) {
    if (!fp.position.allFinite() || !std::isfinite(fp.heading)) continue;
    const auto outline = footprint_outline(fp);
    for (std::size_t i = 0; i < outline.size(); ++i) {
      if (i == 0)
        move_to(cr, fr.to_pixel(outline[i]));
      else
        line_to(cr, fr.to_pixel(outline[i]));
    }
    cairo_close_path(cr);
    const Rgb& c = fp.left ? kLeftColor : kRightColor;
    set_color(cr, c, 0.25);
    cairo_fill_preserve(cr);
    set_color(cr, c, 0.9);
    cairo_set_line_width(cr, 1.3);
    cairo_stroke(cr);
  }
  cairo_restore(cr);
}

// A label next to point q at the first free spot (not over labels, dots or
// feet already placed): eight spots around it, then the same eight twice and
// three times as far with a thin leader line back to the point.
void place_label(cairo_t* cr, const Eigen::Vector2d& q, const std::string& s, const Rgb& color, std::vector<Box>& placed,
                 double size = 11, bool bold = false) {
  const double w = text_width(cr, s, size, bold), h = size;
  const double dx[] = {6, 6, -6 - w, -6 - w, -w / 2, -w / 2, 8, -8 - w};
  const double dy[] = {-6, 6 + h, -6, 6 + h, -8, 10 + h, h / 2, h / 2};
  auto box_at = [&](int k, double r) {
    const double cx = dx[k] + w / 2, cy = dy[k] - h / 2;  // spot centre relative to q
    const double x = q.x() + cx * r - w / 2, y = q.y() + cy * r + h / 2;
    return Box{x, y - h, x + w, y};
  };
  Box chosen = box_at(0, 1);
  double radius = 1;
  bool found = false;
  for (double r : {1.0, 2.2, 3.4}) {
    for (int k = 0; k < 8 && !found; ++k) {
      const Box b = box_at(k, r);
      bool clash = false;
      for (const auto& o : placed) clash = clash || (b.overlap_x(o) > 0 && b.overlap_y(o) > 0);
      if (!clash) chosen = b, radius = r, found = true;
    }
    if (found) break;
  }
  placed.push_back(chosen);
  if (radius > 1) {  // leader line from the point to the label's nearest edge
    const Eigen::Vector2d c((chosen.x0 + chosen.x1) / 2, (chosen.y0 + chosen.y1) / 2);
    const Eigen::Vector2d d = c - q;
    // The segment leaves the label's box (padded by 2 px) at 1 - s of the way.
    const double s_exit = std::min((0.5 * w + 2) / std::max(std::abs(d.x()), 1e-9), (0.5 * h + 2) / std::max(std::abs(d.y()), 1e-9));
    const double t = std::clamp(1.0 - s_exit, 0.0, 1.0);
    cairo_save(cr);
    cairo_move_to(cr, q.x(), q.y());
    cairo_line_to(cr, q.x() + d.x() * t, q.y() + d.y() * t);
    set_color(cr, color, 0.7);
    cairo_set_line_width(cr, 0.8);
    cairo_stroke(cr);
    cairo_restore(cr);
  }
  text(cr, chosen.x0, chosen.y1, s, size, Align::Left, color, 1.0, bold);
}

// Curves with their marked points, then every label: mark labels beside
// their dots and a curve's name beside its end, none over a dot or another label.
void draw_curves(cairo_t* cr, const Scene& scene, const Framing& fr) {
  std::vector<Box> placed;
  cairo_save(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  auto mark_point = [&](const Curve& c, std::size_t m, Eigen::Vector2d& q) {
    const int i = c.marks[m];
    if (i < 0 || i >= static_cast<int>(c.points.size()) || !c.points[static_cast<std::size_t>(i)].allFinite()) return false;
    q = fr.to_pixel(c.points[static_cast<std::size_t>(i)]);
    return true;
  };
  for (const auto& c : scene.curves) {
    if (c.points.empty()) continue;
    bool pen = false;
    for (const auto& p : c.points) {
      if (!p.allFinite()) {
        pen = false;
        continue;
      }
      if (pen)
        line_to(cr, fr.to_pixel(p));
      else
        move_to(cr, fr.to_pixel(p));
      pen = true;
    }
    set_color(cr, c.color);
    cairo_set_line_width(cr, c.width);
    cairo_stroke(cr);
    for (std::size_t m = 0; m < c.marks.size(); ++m) {
      Eigen::Vector2d q;
      if (!mark_point(c, m, q)) continue;
      const double r = c.width + 2.5;
      cairo_arc(cr, q.x(), q.y(), r, 0, 2 * kPi);
      set_color(cr, c.color);
      cairo_fill_preserve(cr);
      set_color(cr, {1, 1, 1});
      cairo_set_line_width(cr, 1.0);
      cairo_stroke(cr);
      placed.push_back({q.x() - r, q.y() - r, q.x() + r, q.y() + r});
    }
  }
  for (const auto& c : scene.curves) {
    for (std::size_t m = 0; m < c.marks.size() && m < c.mark_labels.size(); ++m) {
      Eigen::Vector2d q;
      if (mark_point(c, m, q)) place_label(cr, q, c.mark_labels[m], c.color, placed);
    }
    if (!c.label.empty() && !c.points.empty() && c.points.back().allFinite())
      place_label(cr, fr.to_pixel(c.points.back()), c.label, c.color, placed, 12, true);
  }
  cairo_restore(cr);
}

struct Segment {
  Vec3 a, b;
  Rgb color;
  double depth;
};

// A few tracked devices (no legs: e.g. a headset and two controllers)
// rather than a body: drawn as markers, not as bones.
bool is_device_set(const Skeleton& skel) {
  return !skel.roles.has(Role::LeftHip) && !skel.roles.has(Role::RightHip) && skel.joint_count() <= 8;
}

// Devices as markers: the head as a ring through the head joint and its tip,
// every other device as a dot in its side's colour with a stub towards its
// tip (a controller's pointing direction), thin dashed lines from the head.
void draw_devices(cairo_t* cr, const Figure& f, const Framing& fr) {
  const Skeleton& skel = *f.skeleton;
  const int n = std::min<int>(skel.joint_count(), static_cast<int>(f.positions.size()));
  const auto sides = joint_sides(skel);
  const double w = bone_width(fr);
  const int head = skel.roles[Role::Head];
  const bool tips = f.end_sites.size() == f.positions.size();
  cairo_save(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (int j = 0; j < n && head >= 0 && head < n; ++j) {
    const Vec3 &a = f.positions[static_cast<std::size_t>(head)], &b = f.positions[static_cast<std::size_t>(j)];
    if (j == head || !a.allFinite() || !b.allFinite()) continue;
    const double dash[] = {4, 4};
    cairo_set_dash(cr, dash, 2, 0);
    move_to(cr, fr.to_pixel(a));
    line_to(cr, fr.to_pixel(b));
    set_color(cr, {0.6, 0.6, 0.65});
    cairo_set_line_width(cr, 1.2);
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
  }
  for (int j = 0; j < n; ++j) {
    const auto ju = static_cast<std::size_t>(j);
    const Vec3& p = f.positions[ju];
    if (!p.allFinite()) continue;
    const Rgb c = sides[ju] == Side::Left ? kLeftColor : sides[ju] == Side::Right ? kRightColor : f.color;
    const bool tip = tips && ju < skel.has_end_site.size() && skel.has_end_site[ju] && f.end_sites[ju].allFinite();
    const auto q = fr.to_pixel(p);
    if (j == head) {
      const auto t = tip ? fr.to_pixel(f.end_sites[ju]) : q;
      const double r = std::max(0.6 * (t - q).norm(), 0.07 / fr.metres_per_pixel);
      cairo_arc(cr, (q.x() + t.x()) / 2, (q.y() + t.y()) / 2, r, 0, 2 * kPi);
      set_color(cr, {1, 1, 1});
      cairo_fill_preserve(cr);
      set_color(cr, c);
      cairo_set_line_width(cr, std::max(1.5, w * 0.8));
      cairo_stroke(cr);
      continue;
    }
    if (tip) {
      move_to(cr, q);
      line_to(cr, fr.to_pixel(f.end_sites[ju]));
      set_color(cr, c);
      cairo_set_line_width(cr, w * 1.6);
      cairo_stroke(cr);
    }
    cairo_arc(cr, q.x(), q.y(), w * 1.8, 0, 2 * kPi);
    set_color(cr, c);
    cairo_fill_preserve(cr);
    set_color(cr, {1, 1, 1});
    cairo_set_line_width(cr, 1.2);
    cairo_stroke(cr);
  }
  cairo_restore(cr);
}

void draw_figure(cairo_t* cr, const Figure& f, const Framing& fr) {
  if (!f.skeleton) return;
  if (is_device_set(*f.skeleton)) return draw_devices(cr, f, fr);
  const Skeleton& skel = *f.skeleton;
  const int n = std::min<int>(skel.joint_count(), static_cast<int>(f.positions.size()));
  const auto sides = joint_sides(skel);
  const Vec3 toward = view_basis(fr.view).toward;
  auto color_of = [&](int j) -> Rgb {
    switch (sides[static_cast<std::size_t>(j)]) {
      case Side::Left: return kLeftColor;
      case Side::Right: return kRightColor;
      default: return f.color;
    }
  };
  std::vector<Segment> segs;
  for (int j = 0; j < n; ++j) {
    const auto ju = static_cast<std::size_t>(j);
    const int p = skel.parents[ju];
    if (p >= 0) {
      const Vec3 &a = f.positions[static_cast<std::size_t>(p)], &b = f.positions[ju];
      if (a.allFinite() && b.allFinite() && (a - b).norm() > 1e-6) segs.push_back({a, b, color_of(j), (a + b).dot(toward) / 2});
    }
    if (f.end_sites.size() == f.positions.size() && ju < skel.has_end_site.size() && skel.has_end_site[ju]) {
      const Vec3 &a = f.positions[ju], &b = f.end_sites[ju];
      if (a.allFinite() && b.allFinite() && (a - b).norm() > 1e-6) segs.push_back({a, b, color_of(j), (a + b).dot(toward) / 2});
    }
  }
  // Painter's order: far bones first, so the near leg is drawn over the far one.
  std::stable_sort(segs.begin(), segs.end(), [](const Segment& x, const Segment& y) { return x.depth < y.depth; });

  const double w = bone_width(fr);
  // Depth cue (not from above): near bones wider and full colour, far bones
  // thinner and paler, over the figure's own depth range.
  double near = -1e300, far = 1e300;
  for (const auto& sg : segs) near = std::max(near, sg.depth), far = std::min(far, sg.depth);
  const bool cue = fr.view != View::Top && near - far > 0.05;
  // With alpha, draw into a group so overlapping bones do not darken.
  cairo_save(cr);
  if (f.alpha < 1.0) cairo_push_group(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (const auto& sg : segs) {
    const double t = cue ? (sg.depth - far) / (near - far) : 1.0;  // 0 far .. 1 near
    move_to(cr, fr.to_pixel(sg.a));
    line_to(cr, fr.to_pixel(sg.b));
    const double pale = 0.45 * (1 - t);
    set_color(cr, {sg.color[0] + (1 - sg.color[0]) * pale, sg.color[1] + (1 - sg.color[1]) * pale,
                   sg.color[2] + (1 - sg.color[2]) * pale});
    cairo_set_line_width(cr, cue ? w * (0.7 + 0.6 * t) : w);
    cairo_stroke(cr);
  }
  // Head: a circle through the head joint and its tip, so the figure reads as a person.
  const int head = skel.roles[Role::Head];
  if (head >= 0 && head < n && f.end_sites.size() == f.positions.size() && skel.has_end_site[static_cast<std::size_t>(head)] &&
      f.positions[static_cast<std::size_t>(head)].allFinite() && f.end_sites[static_cast<std::size_t>(head)].allFinite()) {
    const Vec3 a = f.positions[static_cast<std::size_t>(head)], b = f.end_sites[static_cast<std::size_t>(head)];
    const auto c = fr.to_pixel((a + b) / 2);
    const double r = std::max(0.6 * (fr.to_pixel(a) - fr.to_pixel(b)).norm(), 0.07 / fr.metres_per_pixel);
    cairo_arc(cr, c.x(), c.y(), r, 0, 2 * kPi);
    set_color(cr, {1, 1, 1});
    cairo_fill_preserve(cr);
    set_color(cr, f.color);
    cairo_set_line_width(cr, std::max(1.2, w * 0.7));
    cairo_stroke(cr);
  }
  // Joints as small dots.
  for (int j = 0; j < n; ++j) {
    if (!f.positions[static_cast<std::size_t>(j)].allFinite()) continue;  // bad data must not break the picture
    const auto q = fr.to_pixel(f.positions[static_cast<std::size_t>(j)]);
    cairo_arc(cr, q.x(), q.y(), w * 0.75, 0, 2 * kPi);
    set_color(cr, color_of(j));
    cairo_fill(cr);
  }
  if (f.alpha < 1.0) {
    cairo_pop_group_to_source(cr);
    cairo_paint_with_alpha(cr, std::clamp(f.alpha, 0.0, 1.0));
  }
  cairo_restore(cr);
}

void draw_label(cairo_t* cr, const Figure& f, const Framing& fr, const Layout& l) {
  if (f.label.empty() || f.positions.empty() || !f.positions[0].allFinite()) return;
  // Centred under the figure's root, just below the panel's content area.
  (void)l;
  const double x = fr.to_pixel(f.positions[0]).x();
  double lowest = -1e300;
  for (const auto& p : f.positions)
    if (p.allFinite()) lowest = std::max(lowest, fr.to_pixel(p).y());
  if (fr.view != View::Top) lowest = std::max(lowest, fr.to_pixel(Vec3(f.positions[0].x(), 0, f.positions[0].z())).y());
  text(cr, x, std::min(lowest + 18, fr.height - 4.0), f.label, 12, Align::Centre, kInk, std::max(f.alpha, 0.6));
}

// Top-right corner (beside the title) if there is room, else bottom-left.
void draw_scale_bar(cairo_t* cr, const Framing& fr, double title_width) {
  const double target = 0.18 * fr.width * fr.metres_per_pixel;
  static const double kLengths[] = {0.01, 0.02, 0.05, 0.1, 0.2, 0.25, 0.5, 1, 2, 5, 10, 20, 50, 100};
  double len = kLengths[0];
  for (double c : kLengths)
    if (c <= target) len = c;
  const double px = len / fr.metres_per_pixel;
  const bool top = 10 + title_width + 30 + px < fr.width - 10;
  const double x0 = top ? fr.width - 12 - px : 10, y = top ? 22 : fr.height - 10;
  cairo_save(cr);
  set_color(cr, kInk);
  cairo_set_line_width(cr, 1.5);
  cairo_move_to(cr, x0, y - 4);
  cairo_line_to(cr, x0, y);
  cairo_line_to(cr, x0 + px, y);
  cairo_line_to(cr, x0 + px, y - 4);
  cairo_stroke(cr);
  const std::string label = len >= 1 ? format_number(len) + " m" : format_number(len * 100) + " cm";
  text(cr, x0 + px / 2, y - 6, label, 11, Align::Centre, kInk);
  cairo_restore(cr);
}

}  // namespace

std::vector<Vec3> footprint_outline(const Footprint& fp) {
  // A sole in foot coordinates (x lateral, z forward, metres), heel at -0.09,
  // toes at +0.17; the arch side is narrower. Mirrored for the right foot.
  static const double kSole[][2] = {{0.000, -0.095}, {0.030, -0.085}, {0.040, -0.050}, {0.036, 0.000},
                                    {0.048, 0.080},  {0.050, 0.130},  {0.035, 0.165},  {0.000, 0.175},
                                    {-0.030, 0.160}, {-0.042, 0.110}, {-0.030, 0.050}, {-0.022, 0.000},
                                    {-0.032, -0.050}, {-0.028, -0.085}};
  const double c = std::cos(fp.heading), s = std::sin(fp.heading);
  // The big toe (wider side) is towards the body's midline: +x of the foot for
  // the right foot, -x for the left (the character's left is +x).
  const double side = fp.left ? -1.0 : 1.0;
  std::vector<Vec3> out;
  for (const auto& q : kSole) {
    const double x = side * q[0], z = q[1];
    // Rotation about +y by heading: local +z -> (sin h, 0, cos h).
    out.emplace_back(fp.position.x() + c * x + s * z, fp.position.y(), fp.position.z() - s * x + c * z);
  }
  return out;
}

void draw_scene(cairo_t* cr, const Scene& scene, const Framing& fr) {
  const Layout l = layout_of(scene);
  cairo_save(cr);
  cairo_rectangle(cr, 0, 0, fr.width, fr.height);
  cairo_clip(cr);
  if (scene.floor) draw_floor(cr, scene, fr);
  draw_ground(cr, scene, fr);
  draw_footprints(cr, scene, fr);
  // Inactive (translucent) figures first so the active one stays on top.
  std::vector<const Figure*> order;
  for (const auto& f : scene.figures) order.push_back(&f);
  std::stable_sort(order.begin(), order.end(), [](const Figure* a, const Figure* b) { return a->alpha < b->alpha; });
  for (const Figure* f : order) draw_figure(cr, *f, fr);
  draw_curves(cr, scene, fr);
  for (const auto& f : scene.figures) draw_label(cr, f, fr, l);
  double title_w = 0;
  if (!scene.title.empty()) title_w = title(cr, 10, 19, scene.title, 14, fr.width - 20);
  draw_scale_bar(cr, fr, title_w);
  cairo_restore(cr);
}

}  // namespace legwork::render::detail
