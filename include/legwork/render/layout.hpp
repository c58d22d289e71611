#pragma once
// The layout of every picture drawn, as drawn: each text's box, and for
// charts their data areas and legend boxes (pixels, y down). Recorded only
// while a LayoutRecorder is alive on the drawing thread, so tests and checks
// can ask the drawing layer itself whether labels overlap, instead of
// guessing from pixels:
//
//   render::LayoutRecorder rec;
//   eval::write_report(result, "out");             // draws its charts
//   for (const auto& p : rec.pictures())
//     for (const auto& problem : render::layout_problems(p)) std::puts(problem.c_str());
//
// Offline/tool code (allocates).
#include <string>
#include <vector>

namespace legwork::render {

struct Box {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  // Overlap of the two boxes' interiors (pixels along x and y; <= 0: apart).
  double overlap_x(const Box& o) const;
  double overlap_y(const Box& o) const;
};

// One text as drawn: its ink box in picture pixels (rotated text: the box
// around the rotated ink).
struct TextBox {
  std::string text;
  Box box;
};

struct PictureLayout {
  std::string path;  // the picture file; a video's frames: "<video> frame <k>" (k from 0)
  int width = 0, height = 0;
  std::vector<TextBox> texts;
  std::vector<Box> data_areas;  // chart panels (curves and bars are drawn inside)
  std::vector<Box> legends;     // legend boxes
};

// Records the layout of every picture file, and of every frame of every video,
// drawn on this thread while alive.
// One at a time per thread (a second one throws legwork::Error).
class LayoutRecorder {
 public:
  LayoutRecorder();
  ~LayoutRecorder();
  LayoutRecorder(const LayoutRecorder&) = delete;
  LayoutRecorder& operator=(const LayoutRecorder&) = delete;
  const std::vector<PictureLayout>& pictures() const { return pictures_; }

 private:
  friend struct LayoutAccess;
  std::vector<PictureLayout> pictures_;
};

// What a reader would see as a layout fault, one sentence each: two texts
// overlapping by more than `tolerance` pixels in both directions, a legend
// over a data area or another legend, a text or legend reaching outside the
// picture.
std::vector<std::string> layout_problems(const PictureLayout& p, double tolerance = 1.0);

}  // namespace legwork::render
