#include "canvas.hpp"

#include <legwork/core/files.hpp>

#include <cairo-svg.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdio>

namespace legwork::render::detail {

Format format_of(const std::string& path) {
  const auto e = legwork::extension_of(path);
  if (e == ".png") return Format::Png;
  if (e == ".svg") return Format::Svg;
  throw Error("picture '" + path + "' must end in .png or .svg");
}

Canvas::Canvas(const std::string& path, int width, int height)
    : path_(path), format_(format_of(path)), width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > 20000 || height > 20000)
    throw Error("picture '" + path + "': size " + std::to_string(width) + "x" + std::to_string(height) +
                " is out of range (1..20000 pixels)");
  if (format_ == Format::Svg)
    surface_ = cairo_svg_surface_create(path.c_str(), width, height);
  else
    surface_ = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
  if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS) {
    std::string why = cairo_status_to_string(cairo_surface_status(surface_));
    cairo_surface_destroy(surface_);
    throw Error("cannot create picture '" + path + "': " + why);
  }
  cr_ = cairo_create(surface_);
  clear();
  layout_begin(cr_, path, width, height);
}

Canvas::Canvas(int width, int height) : width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > 20000 || height > 20000)
    throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) + " is out of range");
  surface_ = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
  cr_ = cairo_create(surface_);
  clear();
}

Canvas::~Canvas() {
  if (cr_) cairo_destroy(cr_);
  if (surface_) cairo_surface_destroy(surface_);
}

void Canvas::clear() {
  cairo_save(cr_);
  cairo_set_source_rgb(cr_, 1, 1, 1);
  cairo_paint(cr_);
  cairo_restore(cr_);
}

void Canvas::finish() {
  if (cairo_status(cr_) != CAIRO_STATUS_SUCCESS)
    throw Error("drawing '" + path_ + "' failed: " + cairo_status_to_string(cairo_status(cr_)));
  cairo_surface_flush(surface_);
  cairo_status_t st = CAIRO_STATUS_SUCCESS;
  if (format_ == Format::Png) {
    st = cairo_surface_write_to_png(surface_, path_.c_str());
  } else {
    cairo_surface_finish(surface_);
    st = cairo_surface_status(surface_);
  }
  if (st != CAIRO_STATUS_SUCCESS)
    throw Error("cannot write picture '" + path_ + "': " + cairo_status_to_string(st));
}

void set_color(cairo_t* cr, const Rgb& c, double alpha) {
  if (alpha >= 1.0)
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
  else
    cairo_set_source_rgba(cr, c[0], c[1], c[2], alpha);
}

static void select_font(cairo_t* cr, double size, bool bold) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
}

double text_width(cairo_t* cr, const std::string& s, double size, bool bold) {
  select_font(cr, size, bold);
  cairo_text_extents_t ext;
  cairo_text_extents(cr, s.c_str(), &ext);
  return ext.x_advance;
}

double text(cairo_t* cr, double x, double y, const std::string& s, double size, Align align, const Rgb& color,
            double alpha, bool bold) {
  if (s.empty()) return 0;
  const double w = text_width(cr, s, size, bold);
  double x0 = x;
  if (align == Align::Centre) x0 = x - w / 2;
  if (align == Align::Right) x0 = x - w;
  set_color(cr, color, alpha);
  cairo_text_extents_t ink;
  cairo_text_extents(cr, s.c_str(), &ink);
  layout_text(cr, s, x0 + ink.x_bearing, y + ink.y_bearing, ink.width, ink.height);
  cairo_move_to(cr, x0, y);
  cairo_show_text(cr, s.c_str());
  cairo_new_path(cr);
  return w;
}

std::string title_text(const std::string& s) {
  static const char* kExtensions[] = {".bvh", ".csv", ".glb", ".json", ".png", ".svg", ".mp4", ".lwdb", ".tsv", ".md"};
  std::string out;
  std::size_t i = 0;
  while (i < s.size()) {
    const std::size_t end = std::min(s.find(' ', i), s.size());
    std::string word = s.substr(i, end - i);
    // Leading and trailing punctuation stay: "(", "'", ",", ")".
    const std::size_t a = word.find_first_not_of("('\"");
    const std::size_t b = word.find_last_not_of(")',:\"");
    if (a != std::string::npos && b != std::string::npos && b > a) {
      const std::string core = word.substr(a, b - a + 1);
      const auto slash = core.rfind('/');
      bool file = false;
      for (const char* ext : kExtensions)
        file = file || (core.size() > std::strlen(ext) && core.compare(core.size() - std::strlen(ext), std::strlen(ext), ext) == 0);
      if (slash != std::string::npos && slash + 1 < core.size() && file) word = word.substr(0, a) + core.substr(slash + 1) + word.substr(b + 1);
    }
    out += word;
    if (end < s.size()) out += ' ';
    i = end + 1;
  }
  return out;
}

double title(cairo_t* cr, double x, double y, const std::string& s, double size, double max_width) {
  std::string t = title_text(s);
  double sz = size;
  while (sz > 11 && text_width(cr, t, sz, true) > max_width) sz -= 0.5;
  if (text_width(cr, t, sz, true) > max_width) {
    while (t.size() > 1 && text_width(cr, t + "...", sz, true) > max_width) {
      t.pop_back();
      while (!t.empty() && (static_cast<unsigned char>(t.back()) & 0xC0) == 0x80) t.pop_back();  // whole UTF-8 characters
      if (!t.empty() && (static_cast<unsigned char>(t.back()) & 0x80)) t.pop_back();
    }
    t += "...";
  }
  return text(cr, x, y, t, sz, Align::Left, {0.1, 0.1, 0.1}, 1.0, true);
}

double nice_step(double span, int target_count) {
  if (!(span > 0) || target_count < 1) return 1;
  const double raw = span / target_count;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  double nice = 10;
  if (f <= 1.0) nice = 1;
  else if (f <= 2.0) nice = 2;
  else if (f <= 2.5) nice = 2.5;
  else if (f <= 5.0) nice = 5;
  return nice * mag;
}

std::string format_number(double v, int max_decimals) {
  if (std::abs(v) < 1e-12) v = 0;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", max_decimals, v);
  std::string s = buf;
  if (s.find('.') != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}

}  // namespace legwork::render::detail
