// Stacking PNGs: parts one under the other, centred, on white; unreadable
// parts and unwritable outputs are named.
#include <legwork/render/plot.hpp>

#include "render_test_util.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "error_message.hpp"

using namespace legwork;
using namespace legwork::render;
using legwork::render::testing::Image;
using legwork::render::testing::is_background;
using legwork::render::testing::near_color;
using legwork::render::testing::out;
using legwork::render::testing::out_dir;
using legwork::render::testing::Rgba;

using legwork::testdata::message_of;

namespace {

// A width x height PNG filled with one colour.
std::string solid_png(const std::string& name, int width, int height, const Rgb& c) {
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  cairo_t* cr = cairo_create(s);
  cairo_set_source_rgb(cr, c[0], c[1], c[2]);
  cairo_paint(cr);
  cairo_destroy(cr);
  const std::string path = out(name);
  EXPECT_EQ(cairo_surface_write_to_png(s, path.c_str()), CAIRO_STATUS_SUCCESS);
  cairo_surface_destroy(s);
  return path;
}

}  // namespace

TEST(StackPngs, PartsOneUnderTheOtherCentredOnWhite) {
  const Rgb red{1, 0, 0}, blue{0, 0, 1};
  const std::string top = solid_png("stack_top.png", 100, 50, red);
  const std::string bottom = solid_png("stack_bottom.png", 60, 30, blue);
  const std::string path = out("stack.png");
  stack_pngs({top, bottom}, path);
  const Image img(path);
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img.width(), 100);   // the widest part
  EXPECT_EQ(img.height(), 80);   // the parts' heights added
  // Rows 0..49 red; rows 50..79 blue in x 20..79 (centred), white beside it.
  EXPECT_EQ(img.count([&](int, int y, const Rgba& p) { return y < 50 && near_color(p, red, 0.01); }), 100 * 50);
  EXPECT_EQ(img.count([&](int x, int y, const Rgba& p) { return y >= 50 && x >= 20 && x < 80 && near_color(p, blue, 0.01); }),
            60 * 30);
  EXPECT_EQ(img.count([&](int x, int y, const Rgba& p) { return y >= 50 && (x < 20 || x >= 80) && is_background(p); }),
            40 * 30);
}

TEST(StackPngs, ErrorsNameTheFile) {
  const std::string part = solid_png("stack_part.png", 10, 10, {0, 1, 0});
  const std::string missing = out("no-such-part.png");
  std::filesystem::remove(missing);
  EXPECT_EQ(message_of([&] { stack_pngs({part, missing}, out("stack_bad.png")); }),
            "cannot read the intermediate picture " + missing);
  const std::string unwritable = (out_dir() / "no-such-folder" / "stack.png").string();
  EXPECT_EQ(message_of([&] { stack_pngs({part}, unwritable); }), "cannot write " + unwritable);
}
