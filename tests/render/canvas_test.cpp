// The private canvas (src/render/canvas.hpp): PNG and SVG pictures by
// extension, size limits and write errors naming the path, and the text and
// number helpers every picture uses.
#include "../../src/render/canvas.hpp"

#include "render_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "error_message.hpp"

using namespace legwork;
using namespace legwork::render;
using namespace legwork::render::detail;
using legwork::render::testing::Image;
using legwork::render::testing::is_background;
using legwork::render::testing::out;
using legwork::render::testing::out_dir;

using legwork::testdata::message_of;

namespace {

}  // namespace

TEST(RenderCanvas, FormatFollowsTheExtension) {
  EXPECT_EQ(format_of("a/b.png"), Format::Png);
  EXPECT_EQ(format_of("b.svg"), Format::Svg);
  EXPECT_EQ(message_of([] { format_of("pic.jpg"); }), "picture 'pic.jpg' must end in .png or .svg");
  EXPECT_EQ(message_of([] { format_of("pic"); }), "picture 'pic' must end in .png or .svg");
}

TEST(RenderCanvas, PngIsWhiteWithWhatWasDrawn) {
  const std::string path = out("canvas.png");
  std::filesystem::remove(path);
  {
    Canvas c(path, 120, 80);
    EXPECT_EQ(c.width(), 120);
    EXPECT_EQ(c.height(), 80);
    set_color(c.cr(), {0, 0, 0});
    cairo_rectangle(c.cr(), 10, 20, 30, 40);  // x 10..40, y 20..60
    cairo_fill(c.cr());
    c.finish();
  }
  const Image img(path);
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img.width(), 120);
  EXPECT_EQ(img.height(), 80);
  const int black = img.count([](int, int, const auto& p) { return p.r < 0.01 && p.g < 0.01 && p.b < 0.01; });
  EXPECT_EQ(black, 30 * 40);
  EXPECT_EQ(img.count([](int x, int y, const auto& p) {
              return !(x >= 10 && x < 40 && y >= 20 && y < 60) && !is_background(p);
            }),
            0);
}

TEST(RenderCanvas, SvgStreamsToTheFile) {
  const std::string path = out("canvas.svg");
  {
    Canvas c(path, 50, 40);
    cairo_move_to(c.cr(), 0, 0);
    cairo_line_to(c.cr(), 50, 40);
    cairo_stroke(c.cr());
    c.finish();
  }
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("<svg"), std::string::npos);
  EXPECT_NE(ss.str().find("width=\"50\""), std::string::npos);
}

TEST(RenderCanvas, SizeAndWriteErrorsNameThePicture) {
  EXPECT_EQ(message_of([] { Canvas c(out("big.png"), 20001, 10); }),
            "picture '" + out("big.png") + "': size 20001x10 is out of range (1..20000 pixels)");
  EXPECT_EQ(message_of([] { Canvas c(out("none.png"), 10, 0); }),
            "picture '" + out("none.png") + "': size 10x0 is out of range (1..20000 pixels)");
  EXPECT_EQ(message_of([] { Canvas c(-1, 5); }), "image size -1x5 is out of range");
  const std::string missing = (out_dir() / "no-such-folder" / "x.png").string();
  const std::string msg = message_of([&] {
    Canvas c(missing, 10, 10);
    c.finish();
  });
  EXPECT_EQ(msg.rfind("cannot write picture '" + missing + "': ", 0), 0u) << msg;
  // In memory only: white everywhere.
  Canvas mem(4, 3);
  cairo_surface_flush(mem.surface());
  const unsigned char* d = cairo_image_surface_get_data(mem.surface());
  for (int i = 0; i < 3 * cairo_image_surface_get_stride(mem.surface()); ++i) EXPECT_EQ(d[i], 255) << i;
}

TEST(RenderCanvasText, TitlesShortenPathsToFileNames) {
  EXPECT_EQ(title_text("/work/data/cmu/bvh/walking/16_15.bvh"), "16_15.bvh");
  EXPECT_EQ(title_text("walk of (data/a/07_01.bvh), with 'x/y.csv'"), "walk of (07_01.bvh), with 'y.csv'");
  EXPECT_EQ(title_text("left/right and km/h"), "left/right and km/h");  // not files
  EXPECT_EQ(title_text("dir/"), "dir/");
}

TEST(RenderCanvasText, LongTitlesAreCutToTheWidth) {
  Canvas c(400, 40);
  const std::string long_title = "a very long title that cannot possibly fit into one hundred pixels at any size";
  const double w = title(c.cr(), 0, 20, long_title, 14, 100);
  EXPECT_LE(w, 100);
  EXPECT_GT(w, 50);
  // A short title keeps its full size: the width of its bold text at 14 px.
  EXPECT_NEAR(title(c.cr(), 0, 20, "ok", 14, 300), text_width(c.cr(), "ok", 14, true), 1e-9);
  EXPECT_EQ(text(c.cr(), 0, 20, "", 14), 0.0);
  EXPECT_GT(text_width(c.cr(), "abc", 20), text_width(c.cr(), "abc", 10));
}

TEST(RenderCanvasNumbers, NiceStepsAreTheSmallestNiceValueAtLeastTheRawStep) {
  const double nice[] = {1, 2, 2.5, 5, 10};
  for (double span : {0.013, 0.7, 1.0, 3.3, 7.0, 10.0, 42.0, 999.0, 12345.0})
    for (int n : {1, 3, 5, 8}) {
      const double raw = span / n, step = nice_step(span, n);
      EXPECT_GE(step, raw * (1 - 1e-12)) << span << "/" << n;
      const double mag = std::pow(10.0, std::floor(std::log10(step) + 1e-12));
      const double f = step / mag;
      bool is_nice = false;
      double below = 0;  // the largest nice value under step
      for (double k : nice) {
        is_nice = is_nice || std::abs(f - k) < 1e-9;
        if (k < f - 1e-9) below = k;
      }
      EXPECT_TRUE(is_nice) << step;
      const double prev = below > 0 ? below * mag : 5 * mag / 10;
      EXPECT_LT(prev, raw * (1 + 1e-12)) << "a smaller nice step " << prev << " would do for " << raw;
    }
  EXPECT_EQ(nice_step(0, 5), 1);
  EXPECT_EQ(nice_step(10, 0), 1);
}

TEST(RenderCanvasNumbers, NumbersWithoutTrailingZeros) {
  EXPECT_EQ(format_number(0.5), "0.5");
  EXPECT_EQ(format_number(12), "12");
  EXPECT_EQ(format_number(1.25), "1.25");
  EXPECT_EQ(format_number(2.0 / 3.0, 2), "0.67");
  EXPECT_EQ(format_number(-1e-13), "0");
  EXPECT_EQ(format_number(-0.0001, 3), "0");  // rounds to zero: never "-0"
  EXPECT_EQ(format_number(-3.5), "-3.5");
  EXPECT_EQ(format_number(100, 0), "100");
}
