#pragma once
// Private cairo helpers shared by the renderer and the plot helper: a canvas
// that writes .png or .svg by extension, and small text/colour utilities.
#include <legwork/render/render.hpp>

#include <cairo.h>

#include <string>

namespace legwork::render::detail {

enum class Format { Png, Svg };
// .png or .svg from the path's extension; throws legwork::Error otherwise.
Format format_of(const std::string& path);

// One picture being drawn. PNG: an ARGB image surface written on finish();
// SVG: a vector surface streaming to the file. White background.
class Canvas {
 public:
  Canvas(const std::string& path, int width, int height);
  // In-memory image only (video frames); finish() is not needed.
  Canvas(int width, int height);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  cairo_t* cr() const { return cr_; }
  cairo_surface_t* surface() const { return surface_; }
  int width() const { return width_; }
  int height() const { return height_; }
  // Fills the whole canvas white.
  void clear();
  // Writes the file and checks cairo's status; throws legwork::Error naming the path.
  void finish();

 private:
  std::string path_;
  Format format_ = Format::Png;
  int width_ = 0, height_ = 0;
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
};

enum class Align { Left, Centre, Right };
// Draws text with its baseline at y; returns the text's advance width.
double text(cairo_t* cr, double x, double y, const std::string& s, double size, Align align = Align::Left,
            const Rgb& color = {0.1, 0.1, 0.1}, double alpha = 1.0, bool bold = false);
double text_width(cairo_t* cr, const std::string& s, double size, bool bold = false);
// A title as a reader wants it: file paths shortened to their file names
// ("/work/data/cmu/bvh/walking/16_15.bvh" -> "16_15.bvh").
std::string title_text(const std::string& s);
// Draws a bold title at (x, y) within `max_width`: paths shortened, the size
// reduced (down to 11 px) and, if still too wide, the end cut with "...".
double title(cairo_t* cr, double x, double y, const std::string& s, double size, double max_width);
void set_color(cairo_t* cr, const Rgb& c, double alpha = 1.0);
// Layout recording (layout.hpp): a picture file's canvas registers itself;
// text() records its ink box; charts record their data areas and legends.
// No-ops unless a LayoutRecorder is alive on this thread.
void layout_begin(cairo_t* cr, const std::string& path, int width, int height);
// Whether a LayoutRecorder is alive on this thread (names of video frames are built only then).
bool layout_recording();
void layout_text(cairo_t* cr, const std::string& s, double x, double y, double w, double h);
void layout_area(cairo_t* cr, double x, double y, double w, double h, bool legend);
// A "nice" step (1, 2, 2.5 or 5 x 10^k) close to span / target_count.
double nice_step(double span, int target_count);
// Formats a number without trailing zeros ("0.5", "12", "1.25").
std::string format_number(double v, int max_decimals = 3);

}  // namespace legwork::render::detail
