#pragma once
// Pictures: stick figures, contact sheets, trajectories and videos, drawn with
// cairo through orthographic cameras. Offline/tool code: may allocate and
// throw legwork::Error (bad path, ffmpeg missing...). All positions are
// model-space metres. Functions keep no global state and may run on several
// threads at once, except the video writers, which ignore SIGPIPE process-wide
// while they run (so a dying ffmpeg becomes an Error, not a crash).
#include <legwork/core/motion.hpp>

#include <array>
#include <string>
#include <vector>

namespace legwork::render {

// Orthographic views (picture right / picture up in model axes):
//   Side:  +z right, +y up. The camera stands at the character's right side
//          (-x) looking along +x, so the forward direction points right.
//   Front: +x right, +y up. The camera looks along -z at the character's face,
//          so the character's left (+x) is on the picture's right.
//   ThreeQuarter: rotated 45 degrees about y between Side and Front (camera in
//          front-right of the character) and tilted 20 degrees down.
//   Top:   +z right, +x up, looking down -y (walking paths run left to right).
enum class View { Side, Front, ThreeQuarter, Top };
View parse_view(const std::string& name);  // "side", "front", "three-quarter", "top"
std::string view_name(View v);

using Rgb = std::array<double, 3>;  // 0..1

// The colour convention of every picture and chart: the character's left
// side blue, its right side orange (centre bones use the figure's own
// colour), traced paths green. Chosen to stay distinguishable for
// colour-blind viewers; no other mark uses the left or right colour.
inline constexpr Rgb kLeftColor{0.12, 0.40, 0.85};
inline constexpr Rgb kRightColor{0.90, 0.33, 0.05};
inline constexpr Rgb kTraceColor{0.10, 0.55, 0.30};

// Camera axes in model space: unit vectors for picture right, picture up and
// towards the viewer (depth grows towards the viewer).
struct ViewBasis {
  Vec3 right, up, toward;
};
ViewBasis view_basis(View v);
// Model-space point -> view-plane coordinates in metres (right, up).
Eigen::Vector2d project(View v, const Vec3& p);

// Which side of the body a joint belongs to (from the skeleton's roles:
// everything below the left hip / clavicle / shoulder is Left, and so on;
// mirror pairs decide for joints no role covers).
enum class Side { Centre, Left, Right };
std::vector<Side> joint_sides(const Skeleton& skel);

// One stick figure: model-space joint positions over a skeleton.
struct Figure {
  const Skeleton* skeleton = nullptr;
  std::vector<Vec3> positions;  // joint_count entries, metres
  Rgb color{0.15, 0.15, 0.2};
  double alpha = 1.0;  // < 1 draws it translucent ("x-ray" inactive poses)
  std::string label;   // drawn under the figure if not empty
  // Optional model-space End Site tips per joint (empty vector = none; else
  // joint_count entries, used where skeleton->has_end_site[j]): head top, toes.
  std::vector<Vec3> end_sites;
};
// A figure for `pose` over `skel` (positions and End Site tips by FK).
// `skel` must outlive the figure.
Figure make_figure(const Skeleton& skel, ConstPoseRef pose, double alpha = 1.0,
                   std::string label = "");

// A polyline in model space, e.g. a joint trajectory; `marks` are indices of
// points drawn as dots (key frames), `mark_labels` optional text per mark.
struct Curve {
  std::vector<Vec3> points;
  Rgb color = kTraceColor;
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

// Uneven ground under a walk (stairs, a ramp, a hill), drawn as a strip:
// its profile along the walk (model space, heights included; a riser is two
// points above each other) extended `half_width` metres to either side along
// `across` (horizontal). An empty profile draws nothing.
struct GroundStrip {
  std::vector<Vec3> profile;
  Vec3 across = Vec3::UnitX();
  double half_width = 0.45;
};

// Everything drawn in one panel.
struct Scene {
  std::vector<Figure> figures;
  std::vector<Curve> curves;
  std::vector<Footprint> footprints;
  std::string title;
  bool floor = true;  // draw the y = 0 line / grid
  GroundStrip ground;  // drawn over the floor, under everything else
};

struct Camera {
  View view = View::Side;
  int width = 640, height = 480;  // pixels
  double margin = 0.08;           // fraction of the panel kept free around the content
  // Fixed framing (model-space box) instead of auto-framing, if set.
  bool fixed_bounds = false;
  Vec3 bounds_min = Vec3::Zero(), bounds_max = Vec3::Zero();
  // Fixed scale instead of auto-fit (0 = fit the content); equal on both axes.
  double metres_per_pixel = 0;
};

// Where a camera puts model-space points on its picture (pixels, y down).
struct Framing {
  View view = View::Side;
  int width = 0, height = 0;
  double metres_per_pixel = 1;
  Eigen::Vector2d centre_plane = Eigen::Vector2d::Zero();  // view-plane point at centre_pixel
  Eigen::Vector2d centre_pixel = Eigen::Vector2d::Zero();
  Eigen::Vector2d to_pixel(const Vec3& p) const;
};
// The framing render_scene uses: fits all figures, curves, footprints (and
// the floor below them) with the camera's margin, or uses its fixed bounds
// and/or fixed scale.
Framing frame_scene(const Scene& scene, const Camera& cam);

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
  // Turn all poses by one common angle about y so their mean heading faces +z
  // (then "front" shows the face and "side" the profile, whatever the capture's
  // walking direction). Turning within the sequence is kept.
  bool face_forward = true;
};
// Poses are placed side by side along the view's horizontal axis; their root
// horizontal translation is removed so they stand in a row.
void render_contact_sheet(const Skeleton& skel, const std::vector<Pose>& poses,
                          const SheetOptions& opt, const std::string& path);

// Joint trajectory picture: the motion's figure at chosen frames (translucent)
// plus the path of `joint` over all frames, with the chosen frames marked.
void render_trajectory(const Motion& m, int joint, const std::vector<int>& marked_frames,
                       const Camera& cam, const std::string& path);
// The same over frames [first_frame, last_frame] only (last_frame -1 = the
// last frame); marks and labels keep the motion's own frame numbers. An empty
// `marked_frames` marks five evenly spaced frames of the range.
struct TrajectoryOptions {
  int first_frame = 0;
  int last_frame = -1;
  std::string title;  // empty: "<joint> path over N frames (<view> view)"
  std::vector<Footprint> footprints;  // drawn on the floor under the path
};
void render_trajectory(const Motion& m, int joint, const std::vector<int>& marked_frames,
                       const Camera& cam, const std::string& path, const TrajectoryOptions& opt);

// Video of a motion (MP4 through the ffmpeg program; throws legwork::Error if
// ffmpeg is missing or fails). `extra` figures/curves per frame may be added
// by a callback-free overload later; `trace_joint` >= 0 draws its path.
struct VideoOptions {
  Camera camera;        // framing fixed over the whole clip (auto from all frames)
  double fps = 30.0;    // output rate; the motion is resampled
  int trace_joint = -1;
  std::string title;
  // The camera follows each body over the floor (side-by-side videos), so the
  // body fills its panel; the floor grid moves under it. Off: one framing
  // over the whole clip's path.
  bool follow = false;
  GroundStrip ground;  // uneven ground under the motion (not with follow)
};
void render_video(const Motion& m, const VideoOptions& opt, const std::string& path);

// Several motions side by side in one video (e.g. input vs. result vs.
// baseline); each gets its own panel and colour, all with the same duration.
void render_video_side_by_side(const std::vector<const Motion*>& motions,
                               const std::vector<std::string>& labels, const VideoOptions& opt,
                               const std::string& path);

// A still of `video` at `seconds` (clamped into the video by ffmpeg) as PNG,
// for web pages' poster frames. Throws legwork::Error if ffmpeg is missing or
// cannot read the video.
void write_video_still(const std::string& video, const std::string& png, double seconds = 0.5);

}  // namespace legwork::render
