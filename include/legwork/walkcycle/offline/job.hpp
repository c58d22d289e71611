#pragma once
// The walk-cycle tool (`legwork walkcycle`, `legwork walkcycle extract`) as
// library calls: key poses -> cycle -> walk, with the animator's display
// aids (key-pose sheet, arcs, videos, top view) and the JSON report; and
// key-pose extraction from a mocap walk. Prints its figures and the files it
// writes to stdout (progress to stderr) as the command line does; throws
// legwork::Error naming the option on bad input.
#include <string>

namespace legwork::walkcycle {

// Everything `legwork walkcycle` is asked for (file paths empty = not written).
struct WalkJob {
  std::string keys;  // walk.json, or frame list with --from-bvh
  std::string from_bvh;
  std::string skeleton;
  int frames = 0;
  bool frames_given = false;  // --frames on the command line (then 0 and negatives are errors)
  double fps = 0;
  std::string shift;
  std::string path;
  std::string svg_path;
  double straight = 0;
  int steps = -1;
  std::string root = "smooth";  // smooth (legs by IK) or pivot (document 001's root)
  std::string stance_turn = "ball";  // smooth root: ball (the stance foot turns on its ball) or twist (with the body)
  std::string stairs_stride = "fit";  // stairs: fit (one tread per step) or keep (the walk's own stride)
  std::string out;
  std::string cycle_out;
  std::string sheet;
  double spacing = 0.8;
  std::string sheet_views = "front,side";
  std::string active;
  std::string arc;
  std::string arc_out;
  std::string video;
  std::string video_view = "three-quarter";
  std::string slide_video;
  std::string top;
  std::string report;
};
void run_walk_job(const WalkJob& job);

struct ExtractJob {
  std::string input;
  std::string out;
  int frames = 0;
  double fps = 24;
  std::string report;
  std::string sheet;
  std::string name;
};
void run_extract_job(const ExtractJob& job);

}  // namespace legwork::walkcycle
