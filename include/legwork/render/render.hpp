#pragma once
// Pictures: stick figures, contact sheets, trajectories and videos, drawn with
// cairo through orthographic cameras. Offline/tool code: may allocate and
// throw legwork::Error (bad path, ffmpeg missing...).
#include <legwork/core/motion.hpp>

#include <array>
#include <string>
#include <vector>

namespace legwork::render {

// Orthographic views. Side looks along -x (character's +z to the right of
// the picture), Front looks along -z at the character's face, ThreeQuarter is
// rotated 45 degrees about y between them and tilted down, Top looks down -y.
enum class View { Side, Front, ThreeQuarter, Top };
View parse_view(const std::string& name);  // "side", "front", "three-quarter", "top"
std::string view_name(View v);

using Rgb = std::array<double, 3>;  // 0..1

// One stick figure: model-space joint positions over a skeleton.
struct Figure {
  const Skeleton* skeleton = nullptr;
  std::vector<Vec3> positions;  // joint_count entries, metres
  Rgb color{0.15, 0.15, 0.2};
  double alpha = 1.0;  // < 1 draws it translucent ("x-ray" inactive poses)
  std::string label;   // drawn under the figure if not empty
};

// A polyline in model space, e.g. a joint trajectory; `marks` are indices of
// points drawn as dots (key frames), `mark_labels` optional text per mark.
struct Curve {
  std::vector<Vec3> points;
  Rgb color{0.85, 0.3, 0.1};
  double width = 1.5;
  std::vector<int> marks;
  std::vector<std::string> mark_labels;
  std::string label;
};

// A footprint on the floor (top views): position, heading (radians about y,
// 0 = facing +z), and whether it is a left foot.
struct Footprint {
  Vec3 position;
  double heading = 0;
  bool left = true;
};

// Everything drawn in one panel.
struct Scene {
  std::vector<Figure> figures;
  std::vector<Curve> curves;
  std::vector<Footprint> footprints;
  std::string title;
  bool floor = true;  // draw the y = 0 line / grid
};

struct Camera {
  View view = View::Side;
  int width = 640, height = 480;  // pixels
  double margin = 0.08;           // fraction of the panel kept free around the content
  // Fixed framing (model-space box) instead of auto-framing, if set.
  bool fixed_bounds = false;
  Vec3 bounds_min = Vec3::Zero(), bounds_max = Vec3::Zero();
};

// Writes one panel to .png or .svg (chosen by extension).
void render_scene(const Scene& scene, const Camera& cam, const std::string& path);

// Several panels in a grid (rows x cols) in one image (.png or .svg).
struct Panel {
  Scene scene;
  Camera camera;
};
void render_panels(const std::vector<Panel>& panels, int cols, const std::string& path,
                   const std::string& title = "");

// Contact sheet: poses side by side, one row per view.
struct SheetOptions {
  std::vector<View> views{View::Front, View::Side};
  double spacing = 0.8;        // metres between neighbouring poses
  int active = -1;             // index drawn opaque; others translucent (x-ray). -1: all opaque
  double inactive_alpha = 0.3;
  std::vector<std::string> labels;  // per pose, optional
  int panel_height = 360;           // pixels per view row
  std::string title;
};
// Poses are placed side by side along the view's horizontal axis; their root
// horizontal translation is removed so they stand in a row.
void render_contact_sheet(const Skeleton& skel, const std::vector<Pose>& poses,
                          const SheetOptions& opt, const std::string& path);

// Joint trajectory picture: the motion's figure at chosen frames (translucent)
// plus the path of `joint` over all frames, with the chosen frames marked.
void render_trajectory(const Motion& m, int joint, const std::vector<int>& marked_frames,
                       const Camera& cam, const std::string& path);

// Video of a motion (MP4 through the ffmpeg program; throws legwork::Error if
// ffmpeg is missing or fails). `extra` figures/curves per frame may be added
// by a callback-free overload later; `trace_joint` >= 0 draws its path.
struct VideoOptions {
  Camera camera;        // framing fixed over the whole clip (auto from all frames)
  double fps = 30.0;    // output rate; the motion is resampled
  int trace_joint = -1;
  std::string title;
};
void render_video(const Motion& m, const VideoOptions& opt, const std::string& path);

// Several motions side by side in one video (e.g. input vs. result vs.
// baseline); each gets its own panel and colour, all with the same duration.
void render_video_side_by_side(const std::vector<const Motion*>& motions,
                               const std::vector<std::string>& labels, const VideoOptions& opt,
                               const std::string& path);

}  // namespace legwork::render
