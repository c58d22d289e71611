// legwork walkcycle: key poses -> mirrored full cycle -> no-slip walk along a
// path, with the animator's display aids (key-pose sheet, arcs, videos, top
// view) and a JSON report; `legwork walkcycle extract` turns a mocap walk into
// a key-pose file.
#include "command.hpp"

#include <legwork/walkcycle/offline/job.hpp>

#include <memory>

namespace legwork::cli {
namespace {

void register_walkcycle(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "walkcycle",
      "Walk-cycle generator: key poses (contact, down, pass, up) -> mirrored full cycle -> walk without foot\n"
      "slip, straight or along a curved path, with key-pose sheets, arcs, videos and a report.\n"
      "Example: legwork walkcycle --keys data/walks/normal.json --straight 6 --out walk.glb --sheet keys.png \\\n"
      "           --arc LeftHand,LeftToeBase --report walk.json\n"
      "         legwork walkcycle --keys data/walks/sneak.json --path path.json --out sneak.bvh --video sneak.mp4\n"
      "         legwork walkcycle --from-bvh data/cmu/bvh/walking/07_01.bvh --keys 53,60,100,101 --frames 24 --out cycle.bvh\n"
      "         legwork walkcycle extract data/cmu/bvh/walking/07_01.bvh --out my_walk.json");
  auto a = std::make_shared<walkcycle::WalkJob>();
  cmd->add_option("--keys", a->keys, "walk key-pose file (JSON, see docs/walkcycle.md); with --from-bvh: frames C,D,P,U");
  cmd->add_option("--from-bvh", a->from_bvh, "take the key poses from frames of this BVH (frame numbers in --keys, counted from the file's first frame, the CMU T-pose)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--skeleton", a->skeleton, "BVH whose skeleton the walk is for (default: the walk's \"skeleton\")")
      ->check(CLI::ExistingFile);
  cmd->add_option("--frames", a->frames, "frames per cycle (two steps), even; default: the walk's (24)");
  cmd->add_option("--fps", a->fps, "output frame rate of the walk (default: the walk's)")->check(CLI::Range(1.0, 480.0));
  cmd->add_option("--shift", a->shift, "key delays in frames per joint, e.g. LeftShoulder=0,LeftArm=1,LeftForeArm=2 "
                                       "(the mirrored joint gets the same)");
  cmd->add_option("--path", a->path, "walk along this path (JSON: polyline, bezier, catmull_rom or svg)")->check(CLI::ExistingFile);
  cmd->add_option("--svg-path", a->svg_path, "walk along this SVG path string, metres (x = left, y = forward)");
  cmd->add_option("--straight", a->straight, "walk this many metres straight ahead (+z)")->check(positive_number());
  cmd->add_option("--steps", a->steps, "walk exactly this many steps straight ahead, the stop step included (1 to 100000)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--root", a->root, "smooth: the root travels evenly, legs by IK (default); pivot: document 001's root, "
                                     "pushed so the stance foot stays put (lunges and stalls)")
      ->check(CLI::IsMember({"smooth", "pivot"}));
  cmd->add_option("--stance-turn", a->stance_turn, "smooth root on turns: ball: the stance foot keeps its yaw while the heel "
                                                   "is down and turns on its ball (default); twist: it turns with the body")
      ->check(CLI::IsMember({"ball", "twist"}));
  cmd->add_option("--stairs-stride", a->stairs_stride, "on stairs: fit: one tread per step, the stride shortened to the "
                                                       "treads (default); keep: the walk's own stride (two treads at a time, crouching)")
      ->check(CLI::IsMember({"fit", "keep"}));
  output_file(cmd->add_option("--out,-o", a->out, "the walk (or, with no path, the in-place cycle): .bvh or .glb"));
  output_file(cmd->add_option("--cycle-out", a->cycle_out, "the in-place loop (frame N = frame 0 left out): .bvh or .glb"));
  output_file(cmd->add_option("--sheet", a->sheet, "key-pose sheet: the five poses of a step side by side (.png or .svg)"));
  cmd->add_option("--spacing", a->spacing, "metres between poses on the sheet / in the sliding video")->check(positive_number());
  cmd->add_option("--sheet-views", a->sheet_views, "views of the sheet, comma-separated (front, side, three-quarter, top)");
  cmd->add_option("--active", a->active, "sheet: draw this pose opaque, the others x-ray (contact, down, pass, up, next)");
  cmd->add_option("--arc", a->arc, "trace these joints over the cycle: CSV + SVG/PNG with key frames marked, e.g. LeftHand,LeftToeBase");
  output_file(cmd->add_option("--arc-out", a->arc_out, "file prefix for the arcs (default: --out without extension)"));
  output_file(cmd->add_option("--video", a->video, "MP4 of the walk (needs ffmpeg)"));
  cmd->add_option("--video-view", a->video_view, "view of --video: side, front, three-quarter, top");
  output_file(cmd->add_option("--slide-video", a->slide_video, "MP4 of the model sliding through the translucent key poses"));
  output_file(cmd->add_option("--top", a->top, "top view of the walk with the path and footprints (.png or .svg)"));
  output_file(cmd->add_option("--report", a->report, "JSON report: stance_slip_mm_max, loop_seam_error, steps, frames, arcs..."));

  auto* ext = cmd->add_subcommand("extract",
                                  "Detect contact, down, pass and up in a real walking clip (CMU BVH) and write a\n"
                                  "key-pose file to start a stylised walk from.\n"
                                  "Example: legwork walkcycle extract data/cmu/bvh/walking/07_01.bvh --out 07_01_keys.json --sheet keys.png");
  auto e = std::make_shared<walkcycle::ExtractJob>();
  ext->add_option("input", e->input, "walking clip (BVH; frame 0, the CMU T-pose, is dropped)")->required()->check(CLI::ExistingFile);
  output_file(ext->add_option("--out,-o", e->out, "key-pose file to write (JSON)"))->required();
  ext->add_option("--frames", e->frames, "frames per cycle (default: the clip's cycle at --fps, even)");
  ext->add_option("--fps", e->fps, "frame rate of the key-pose file (default 24)")->check(CLI::Range(1.0, 480.0));
  ext->add_option("--name", e->name, "walk name (default: the clip's file name)");
  output_file(ext->add_option("--sheet", e->sheet, "also draw the extracted key poses (.png or .svg)"));
  output_file(ext->add_option("--report", e->report, "JSON report: detected steps, cycle length, resynthesis error"));
  ext->callback([e] { walkcycle::run_extract_job(*e); });
  cmd->callback([a, ext, cmd] {
    if (ext->parsed()) return;
    a->frames_given = cmd->count("--frames") > 0;
    walkcycle::run_walk_job(*a);
  });
}

LEGWORK_COMMAND(register_walkcycle, 40);

}  // namespace
}  // namespace legwork::cli
