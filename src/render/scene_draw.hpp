#pragma once
// Private: drawing a Scene through a Framing onto a cairo context.
#include "canvas.hpp"

#include <functional>
#include <vector>

namespace legwork::render::detail {

// Pixels reserved above (title) and below (figure labels) the content.
struct Layout {
  double top = 0, bottom = 0;
};
Layout layout_of(const Scene& scene);

// View-plane box (metres) of the scene's content and its floor shadow; false if empty.
bool plane_bounds(const Scene& scene, View view, Eigen::Vector2d& lo, Eigen::Vector2d& hi);
void for_each_content_point(const Scene& scene, const std::function<void(const Vec3&)>& fn);
// Model-space outline of a footprint (a sole shape on the floor, ~0.26 m long).
std::vector<Vec3> footprint_outline(const Footprint& fp);

// Draws the scene (floor, footprints, curves, figures, labels, title, scale
// bar) into the rectangle [0,fr.width] x [0,fr.height] of the current cairo
// user space. The caller paints the background.
void draw_scene(cairo_t* cr, const Scene& scene, const Framing& fr);

}  // namespace legwork::render::detail
