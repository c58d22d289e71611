// Stacking finished pictures into one (reports put a plot over a strip of poses).
#include <legwork/render/plot.hpp>

#include <cairo.h>

#include <algorithm>

namespace legwork::render {

// Stacks PNG images vertically into one PNG (white background).
void stack_pngs(const std::vector<std::string>& parts, const std::string& out) {
  std::vector<cairo_surface_t*> imgs;
  int w = 0, h = 0;
  for (const auto& p : parts) {
    cairo_surface_t* s = cairo_image_surface_create_from_png(p.c_str());
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
      for (auto* i : imgs) cairo_surface_destroy(i);
      cairo_surface_destroy(s);
      throw Error("cannot read the intermediate picture " + p);
    }
    w = std::max(w, cairo_image_surface_get_width(s));
    h += cairo_image_surface_get_height(s);
    imgs.push_back(s);
  }
  cairo_surface_t* dst = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  cairo_t* cr = cairo_create(dst);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  int y = 0;
  for (auto* s : imgs) {
    cairo_set_source_surface(cr, s, (w - cairo_image_surface_get_width(s)) / 2.0, y);
    cairo_paint(cr);
    y += cairo_image_surface_get_height(s);
    cairo_surface_destroy(s);
  }
  cairo_destroy(cr);
  const auto st = cairo_surface_write_to_png(dst, out.c_str());
  cairo_surface_destroy(dst);
  if (st != CAIRO_STATUS_SUCCESS) throw Error("cannot write " + out);
}

}  // namespace legwork::render
