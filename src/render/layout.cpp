// Layout recording for pictures (see layout.hpp) and the private hooks the
// canvas and the chart code call while drawing.
#include <legwork/render/layout.hpp>

#include "canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace legwork::render {

namespace {
thread_local LayoutRecorder* g_recorder = nullptr;
const cairo_user_data_key_t kPictureKey{};  // cr -> 1 + index of its picture

std::string describe(const Box& b) {
  char s[96];
  std::snprintf(s, sizeof s, "[%.0f,%.0f]-[%.0f,%.0f]", b.x0, b.y0, b.x1, b.y1);
  return s;
}
}  // namespace

struct LayoutAccess {
  static PictureLayout* picture(cairo_t* cr) {
    if (!g_recorder) return nullptr;
    const auto tag = reinterpret_cast<std::uintptr_t>(cairo_get_user_data(cr, &kPictureKey));
    if (tag == 0 || tag > g_recorder->pictures_.size()) return nullptr;
    return &g_recorder->pictures_[tag - 1];
  }
  static void begin(cairo_t* cr, const std::string& path, int width, int height) {
    if (!g_recorder) return;
    g_recorder->pictures_.push_back({path, width, height, {}, {}, {}});
    cairo_set_user_data(cr, &kPictureKey, reinterpret_cast<void*>(static_cast<std::uintptr_t>(g_recorder->pictures_.size())),
                        nullptr);
  }
};

double Box::overlap_x(const Box& o) const { return std::min(x1, o.x1) - std::max(x0, o.x0); }
double Box::overlap_y(const Box& o) const { return std::min(y1, o.y1) - std::max(y0, o.y0); }

LayoutRecorder::LayoutRecorder() {
  if (g_recorder) throw Error("a LayoutRecorder is already recording on this thread");
  g_recorder = this;
}

LayoutRecorder::~LayoutRecorder() { g_recorder = nullptr; }

std::vector<std::string> layout_problems(const PictureLayout& p, double tolerance) {
  std::vector<std::string> out;
  const std::string where = p.path.empty() ? "picture" : p.path;
  auto overlapping = [&](const Box& a, const Box& b) { return a.overlap_x(b) > tolerance && a.overlap_y(b) > tolerance; };
  auto outside = [&](const Box& b) {
    return b.x0 < -tolerance || b.y0 < -tolerance || b.x1 > p.width + tolerance || b.y1 > p.height + tolerance;
  };
  for (std::size_t i = 0; i < p.texts.size(); ++i) {
    const TextBox& a = p.texts[i];
    if (outside(a.box)) out.push_back(where + ": text '" + a.text + "' " + describe(a.box) + " reaches outside the picture");
    for (std::size_t j = i + 1; j < p.texts.size(); ++j)
      if (overlapping(a.box, p.texts[j].box))
        out.push_back(where + ": text '" + a.text + "' " + describe(a.box) + " overlaps '" + p.texts[j].text + "' " +
                      describe(p.texts[j].box));
  }
  for (std::size_t i = 0; i < p.legends.size(); ++i) {
    const Box& l = p.legends[i];
    if (outside(l)) out.push_back(where + ": legend " + describe(l) + " reaches outside the picture");
    for (const Box& d : p.data_areas)
      if (overlapping(l, d)) out.push_back(where + ": legend " + describe(l) + " covers the data area " + describe(d));
    for (std::size_t j = i + 1; j < p.legends.size(); ++j)
      if (overlapping(l, p.legends[j])) out.push_back(where + ": legend " + describe(l) + " overlaps legend " + describe(p.legends[j]));
  }
  return out;
}

namespace detail {

void layout_begin(cairo_t* cr, const std::string& path, int width, int height) { LayoutAccess::begin(cr, path, width, height); }
bool layout_recording() { return g_recorder != nullptr; }

// The device-space box around a user-space rectangle (handles rotation).
Box device_box(cairo_t* cr, double x, double y, double w, double h) {
  double xs[4] = {x, x + w, x, x + w}, ys[4] = {y, y, y + h, y + h};
  Box b{INFINITY, INFINITY, -INFINITY, -INFINITY};
  for (int k = 0; k < 4; ++k) {
    cairo_user_to_device(cr, &xs[k], &ys[k]);
    b.x0 = std::min(b.x0, xs[k]), b.x1 = std::max(b.x1, xs[k]);
    b.y0 = std::min(b.y0, ys[k]), b.y1 = std::max(b.y1, ys[k]);
  }
  return b;
}

void layout_text(cairo_t* cr, const std::string& s, double x, double y, double w, double h) {
  if (PictureLayout* p = LayoutAccess::picture(cr)) p->texts.push_back({s, device_box(cr, x, y, w, h)});
}

void layout_area(cairo_t* cr, double x, double y, double w, double h, bool legend) {
  if (PictureLayout* p = LayoutAccess::picture(cr)) (legend ? p->legends : p->data_areas).push_back(device_box(cr, x, y, w, h));
}

}  // namespace detail
}  // namespace legwork::render
