#pragma once
// Helpers for render tests: read PNGs back through cairo and count pixels.
#include <legwork/io/bvh.hpp>
#include <legwork/render/render.hpp>

#include <cairo.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

namespace legwork::render::testing {

// Output folder for test pictures (kept for inspection).
inline std::filesystem::path out_dir() {
  auto d = std::filesystem::temp_directory_path() / "legwork-render-test";
  std::filesystem::create_directories(d);
  return d;
}

// The sample walk 07_01 as the file has it (T-pose frame kept), loaded once.
inline const Motion& walk_07_01() {
  static const Motion m = io::load_bvh(std::string(LEGWORK_SOURCE_DIR) + "/data/cmu/bvh/walking/07_01.bvh");
  return m;
}

// A camera on view v making a width x height picture.
inline Camera camera(View v, int width, int height) {
  Camera cam;
  cam.view = v;
  cam.width = width;
  cam.height = height;
  return cam;
}

struct Rgba {
  double r, g, b, a;
};

// A decoded PNG (throws via gtest expectations if it does not decode).
class Image {
 public:
  explicit Image(const std::string& path)
      : surf_(cairo_image_surface_create_from_png(path.c_str()), cairo_surface_destroy) {}
  bool ok() const { return cairo_surface_status(surf_.get()) == CAIRO_STATUS_SUCCESS; }
  int width() const { return cairo_image_surface_get_width(surf_.get()); }
  int height() const { return cairo_image_surface_get_height(surf_.get()); }
  Rgba at(int x, int y) const {
    const unsigned char* d = cairo_image_surface_get_data(surf_.get());
    const int stride = cairo_image_surface_get_stride(surf_.get());
    std::uint32_t px = 0;
    std::memcpy(&px, d + y * stride + x * 4, 4);
    const double a = ((px >> 24) & 255) / 255.0;
    auto ch = [&](int s) { return a > 0 ? ((px >> s) & 255) / 255.0 / a : 1.0; };  // un-premultiply
    if (cairo_image_surface_get_format(surf_.get()) == CAIRO_FORMAT_RGB24) return {((px >> 16) & 255) / 255.0, ((px >> 8) & 255) / 255.0, (px & 255) / 255.0, 1.0};
    return {ch(16), ch(8), ch(0), a};
  }
  // Pixels for which pred holds.
  int count(const std::function<bool(int, int, const Rgba&)>& pred) const {
    int n = 0;
    for (int y = 0; y < height(); ++y)
      for (int x = 0; x < width(); ++x)
        if (pred(x, y, at(x, y))) ++n;
    return n;
  }

 private:
  std::unique_ptr<cairo_surface_t, void (*)(cairo_surface_t*)> surf_;
};

// out_dir()/name as a string.
inline std::string out(const std::string& name) { return (out_dir() / name).string(); }

// Renders `s` to out(name) and decodes it.
inline Image rendered(const Scene& s, const Camera& cam, const std::string& name) {
  render_scene(s, cam, out(name));
  return Image(out(name));
}

inline bool is_background(const Rgba& p) { return p.r > 0.97 && p.g > 0.97 && p.b > 0.97; }
// Within tol of colour c (per channel); anti-aliased edges are excluded.
inline bool near_color(const Rgba& p, const Rgb& c, double tol = 0.08) {
  return std::abs(p.r - c[0]) < tol && std::abs(p.g - c[1]) < tol && std::abs(p.b - c[2]) < tol;
}

}  // namespace legwork::render::testing
