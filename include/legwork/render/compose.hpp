#pragma once
// Composed pictures and videos built from the render primitives: frame
// sampling and fitted picture sizes for motion pictures, rough footprints, a
// joint's arc over key poses, a "sliding" key-pose video and a walk seen from
// above. Used by the command line; each writes files and returns nothing.
#include <legwork/render/render.hpp>

#include <functional>
#include <string>
#include <vector>

namespace legwork::render {

// Footprints for pictures: runs of frames (>= 0.1 s) where a foot is in
// contact by foot_contacts (core/contacts.hpp, the detector every module
// uses), one print per run at the run's mean ankle position, turned along
// ankle->toe. Empty when the skeleton has no ankles.
std::vector<Footprint> detect_footprints(const Motion& m, int first, int last);

// Frames first..last sampled every `every` frames (or up to 6 evenly, first and
// last included, when every <= 0). With every > 0 the last frame is added
// unless it is less than every/2 after the last sample.
std::vector<int> sample_frames(int first, int last, int every);

// A picture height that suits the content's aspect in this view (less empty
// space for long flat paths seen from above), between 240 and 960 pixels, even.
int fitted_height(const Motion& m, int first, int last, View view, int width);

// A joint's closed arc (`arc.points`, marks = key indices) over translucent
// `ghosts`, side and front view: writes `base`.svg and `base`.png.
void render_arc(const Skeleton& skel, const std::vector<Pose>& ghosts, const Curve& arc, const std::string& title,
                const std::string& base);

// Sliding display (animator's "sliding" + "x-ray"): the animated figure slides
// through the translucent key poses spread `spacing` metres apart along +z.
// `key_times` (one per pose, increasing) are the poses' times; `sample(t, out)`
// poses the figure at time t in [0, duration]. MP4 at 24 fps, 4 video frames
// per unit of time, through the ffmpeg program.
struct SlideVideo {
  std::vector<Pose> key_poses;
  std::vector<std::string> labels;
  std::vector<double> key_times;
  std::function<void(double, PoseRef)> sample;
  double duration = 0;
  double spacing = 0.8;
};
void render_slide_video(const Skeleton& skel, const SlideVideo& v, const std::string& path);

// A walk from above: the path (if any, grey), the root's track, footprints and
// a few translucent figures along the way (800 x 800).
void render_walk_top(const Motion& walk, const std::vector<Vec3>* path, const std::vector<Footprint>& footprints,
                     const std::string& title, const std::string& out);

}  // namespace legwork::render
