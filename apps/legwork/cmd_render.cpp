// legwork render: pictures (contact sheets, single frames, joint paths) and
// videos of a motion file.
#include "command.hpp"

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/io/text.hpp>
#include <legwork/render/compose.hpp>
#include <legwork/walkcycle/keys.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

namespace legwork::cli {
namespace {

struct RenderArgs {
  MotionInput in;
  std::string out;
  std::string view;  // empty = the command's default
  std::string frames;
  std::string trace;
  int every = 0;  // 0 = about six poses / marks over the range
  int width = 0, height = 0;
  double fps = 30;
  std::string title;
  std::vector<std::string> compare;  // more motions for a side-by-side video
  bool footprints = false;
  bool follow = false;
};

// A joint by exact name or by role name (e.g. left_ankle); the error lists the valid names.
int find_trace_joint(const Skeleton& skel, const std::string& name) {
  if (const int j = walkcycle::find_joint_or_role(skel, name); j >= 0) return j;
  std::string valid;
  for (const auto& n : skel.names) valid += (valid.empty() ? "" : ", ") + n;
  throw Error("--trace: unknown joint '" + name + "'; valid joints: " + valid +
              " (role names such as left_ankle also work)");
}

void run_render(const RenderArgs& a) {
  require_extension("--out", a.out, {".png", ".svg", ".mp4"});
  const std::string ext = io::extension_of(a.out);
  const auto view = a.view.empty() ? render::View::Side : render::parse_view(a.view);
  const auto file = a.in.load();
  const Motion& m = file.motion;
  if (m.frame_count() == 0) throw Error("'" + a.in.path + "' has no frames");
  auto [first, last] = a.frames.empty() ? std::pair<int, int>{0, m.frame_count() - 1}
                                        : io::parse_frame_range(a.frames, m.frame_count());
  const int trace = a.trace.empty() ? -1 : find_trace_joint(m.skeleton, a.trace);
  const std::string clip = std::filesystem::path(a.in.path).stem().string();
  if (a.footprints && (trace < 0 || ext == ".mp4"))
    throw Error("--footprints needs --trace JOINT and a .png/.svg output (it draws under the joint's path)");

  if (a.follow && ext != ".mp4") throw Error("--follow is for videos (--out .mp4): a picture has no camera to move");
  if (ext == ".mp4") {
    render::VideoOptions opt;
    opt.camera.view = view;
    opt.camera.width = a.width > 0 ? a.width : 640;
    opt.camera.height = a.height > 0 ? a.height : 480;
    opt.fps = a.fps;
    opt.trace_joint = trace;
    opt.follow = a.follow;
    opt.title = !a.title.empty() ? a.title : clip + " (" + render::view_name(view) + " view)";
    const Motion part = (first == 0 && last == m.frame_count() - 1) ? m : trim(m, first, last);
    if (a.compare.empty()) {
      render::render_video(part, opt, a.out);
    } else {
      // Side by side: this motion first, then each --compare file, same frames and options.
      std::vector<Motion> others;
      std::vector<std::string> labels{clip};
      for (const auto& path : a.compare) {
        MotionInput other = a.in;
        other.path = path;
        Motion o = other.load().motion;
        if (o.frame_count() == 0) throw Error("'" + path + "' has no frames");
        const int b = std::min(last, o.frame_count() - 1);
        others.push_back(first <= b ? trim(o, std::min(first, b), b) : o);
        labels.push_back(std::filesystem::path(path).stem().string());
      }
      std::vector<const Motion*> all{&part};
      for (const auto& o : others) all.push_back(&o);
      if (a.title.empty()) opt.title = render::view_name(view) + " view";
      render::render_video_side_by_side(all, labels, opt, a.out);
    }
    std::printf("%d source frames (%d:%d) at %.4g Hz -> %.4g fps video, %dx%d\n", last - first + 1, first, last, m.fps,
                a.fps, opt.camera.width, opt.camera.height);
    announce("video", a.out);
    return;
  }
  if (trace >= 0) {
    render::Camera cam;
    cam.view = view;
    cam.width = a.width > 0 ? a.width : 960;
    cam.height = a.height > 0 ? a.height : render::fitted_height(m, first, last, view, cam.width);
    render::TrajectoryOptions opt;
    opt.first_frame = first;
    opt.last_frame = last;
    opt.title = a.title;
    if (a.footprints) opt.footprints = render::detect_footprints(m, first, last);
    render::render_trajectory(m, trace, render::sample_frames(first, last, a.every), cam, a.out, opt);
    announce("trajectory", a.out);
    return;
  }
  render::SheetOptions opt;
  if (!a.view.empty()) opt.views = {view};
  if (a.height > 0) opt.panel_height = a.height;
  std::vector<Pose> poses;
  for (int f : render::sample_frames(first, last, a.every)) {
    const auto fr = m.frame(f);
    Pose p;
    p.rotations.assign(fr.rotations.begin(), fr.rotations.end());
    p.translations.assign(fr.translations.begin(), fr.translations.end());
    poses.push_back(std::move(p));
    opt.labels.push_back("frame " + std::to_string(f));
  }
  // One frame (A:A) is a one-pose sheet: same facing and framing rules.
  opt.title = !a.title.empty() ? a.title
              : first == last  ? clip + ": frame " + std::to_string(first)
                               : clip + ": frames " + std::to_string(first) + ":" + std::to_string(last) + " (" +
                                     std::to_string(poses.size()) + " poses)";
  render::render_contact_sheet(m.skeleton, poses, opt, a.out);
  announce(first == last ? "frame" : "contact sheet", a.out);
}

void register_render(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "render",
      "Draw a motion as stick figures (left side blue, right side orange): a contact sheet of poses\n"
      "(.png/.svg), a single frame (--frames A:A), a joint's path over translucent figures (--trace),\n"
      "or a video (.mp4, needs the ffmpeg program).\n"
      "Examples:\n"
      "  legwork render data/cmu/bvh/walking/07_01.bvh --out sheet.png --frames 1:120 --every 20\n"
      "  legwork render data/cmu/bvh/walking/07_01.bvh --out foot.svg --trace LeftFoot --frames 1:\n"
      "  legwork render data/cmu/bvh/walking/07_01.bvh --out steps.png --trace Hips --view top --footprints\n"
      "  legwork render data/cmu/bvh/walking/07_01.bvh --out walk.mp4 --view three-quarter --trace LeftFoot");
  auto a = std::make_shared<RenderArgs>();
  a->in.add_options(cmd);
  output_file(cmd->add_option("--out,-o", a->out, "output: .png or .svg (picture) or .mp4 (video)"))->required();
  cmd->add_option("--view", a->view,
                  "side (forward to the right), front (facing you: the character's left on your right), "
                  "three-quarter, top. Default: side; contact sheets show front and side rows unless given");
  cmd->add_option("--frames", a->frames, "frames A:B (inclusive, either side optional; A:A = one frame)");
  cmd->add_option("--trace", a->trace, "draw this joint's path (joint name, or a role name such as left_ankle)");
  cmd->add_option("--every", a->every, "take every Nth frame for sheet poses / path marks (default: ~6 over the range)")
      ->check(positive_number());
  cmd->add_option("--width", a->width, "picture/video width in pixels (video: even)")->check(CLI::Range(16, 8192));
  cmd->add_option("--height", a->height,
                  "picture/video height in pixels (contact sheets: per view row, width follows the poses)")
      ->check(CLI::Range(16, 8192));
  cmd->add_option("--fps", a->fps, "video frame rate (the motion is resampled), default 30")->check(CLI::Range(1.0, 240.0));
  cmd->add_option("--title", a->title, "title text (default: clip name and frames)");
  cmd->add_option("--compare", a->compare,
                  "video only: more BVH files drawn side by side with IN (same frames, view and options)")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--footprints", a->footprints,
                "with --trace (pictures): draw rough footprints where each ankle rests (best with --view top)");
  cmd->add_flag("--follow", a->follow,
                "video only: the camera follows the body over the floor, so it fills the frame (default: one "
                "framing over the whole path)");
  cmd->callback([a] { run_render(*a); });
}

LEGWORK_COMMAND(register_render, 40);

}  // namespace
}  // namespace legwork::cli
