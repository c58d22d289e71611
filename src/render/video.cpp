// Videos: cairo image frames piped as raw BGRA into the ffmpeg program.
#include "scene_draw.hpp"

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/io/progress.hpp>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace legwork::render {

namespace {

// Longest video rendered: 1,000,000 frames (9 hours at 30 fps).
constexpr double kMaxVideoFrames = 1e6;

using detail::Align;

// The ffmpeg program: $LEGWORK_FFMPEG if set, else the first "ffmpeg" on PATH.
std::string find_ffmpeg() {
  if (const char* env = std::getenv("LEGWORK_FFMPEG")) {
    if (std::filesystem::exists(env)) return env;
    throw Error(std::string("LEGWORK_FFMPEG='") + env + "' does not exist; cannot write video");
  }
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    auto end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    const std::filesystem::path cand = std::filesystem::path(dirs.substr(start, end - start)) / "ffmpeg";
    std::error_code ec;
    if (!dirs.substr(start, end - start).empty() && std::filesystem::is_regular_file(cand, ec)) return cand.string();
    start = end + 1;
  }
  throw Error("the ffmpeg program was not found on PATH; install ffmpeg (e.g. apt install ffmpeg) to write .mp4 videos");
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'')
      q += "'\\''";
    else
      q += c;
  }
  return q + "'";
}

// An ffmpeg process reading raw BGRA frames on stdin and writing H.264 MP4.
class FfmpegPipe {
 public:
  FfmpegPipe(const std::string& out, int w, int h, double fps) : out_(out) {
    const std::string cmd = shell_quote(find_ffmpeg()) + " -y -loglevel error -f rawvideo -pix_fmt bgra -s " +
                            std::to_string(w) + "x" + std::to_string(h) + " -r " + detail::format_number(fps, 4) +
                            " -i - -c:v libx264 -pix_fmt yuv420p -movflags +faststart " + shell_quote(out);
    // A dying ffmpeg must give a write error, not kill us with SIGPIPE.
    old_ = std::signal(SIGPIPE, SIG_IGN);
    pipe_ = popen(cmd.c_str(), "w");
    if (!pipe_) {
      std::signal(SIGPIPE, old_);
      throw Error("cannot start ffmpeg to write '" + out + "'");
    }
  }
  ~FfmpegPipe() {
    if (pipe_) pclose(pipe_);
    std::signal(SIGPIPE, old_);
  }
  FfmpegPipe(const FfmpegPipe&) = delete;
  FfmpegPipe& operator=(const FfmpegPipe&) = delete;

  void write_frame(cairo_surface_t* s) {
    cairo_surface_flush(s);
    const int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
    const int stride = cairo_image_surface_get_stride(s);
    const unsigned char* data = cairo_image_surface_get_data(s);
    // cairo's ARGB32 is native-endian 32-bit: B,G,R,A bytes on little-endian machines.
    for (int y = 0; y < h; ++y)
      if (std::fwrite(data + static_cast<std::ptrdiff_t>(y) * stride, 4, static_cast<std::size_t>(w), pipe_) !=
          static_cast<std::size_t>(w))
        throw Error("ffmpeg stopped reading frames while writing '" + out_ + "' (see its message above)");
  }
  void close() {
    const int rc = pclose(pipe_);
    pipe_ = nullptr;
    if (rc != 0)
      throw Error("ffmpeg failed writing '" + out_ + "' (exit status " + std::to_string(rc) +
                  "); its message is above");
  }

 private:
  std::string out_;
  FILE* pipe_ = nullptr;
  void (*old_)(int) = SIG_DFL;
};

// One motion's panel: its poses at the output times and fixed framing.
struct Track {
  const Motion* motion = nullptr;
  std::string label;
  Rgb color;
  Framing framing;
  std::vector<Vec3> trace;  // joint path at the motion's own frames
};

Scene frame_scene_of(const Track& t, double time, const VideoOptions& opt, Pose& pose, bool with_title) {
  const Motion& m = *t.motion;
  sample_motion(m, std::min(time, m.duration()), pose.ref());
  Scene s;
  Figure f = make_figure(m.skeleton, pose);
  f.color = t.color;
  s.figures.push_back(std::move(f));
  if (!t.trace.empty()) {
    Curve all;
    all.points = t.trace;
    all.color = {0.75, 0.88, 0.78};
    all.width = 1.5;
    Curve done;
    const auto upto = static_cast<std::size_t>(std::clamp(time * m.fps, 0.0, double(m.frame_count() - 1))) + 1;
    done.points.assign(t.trace.begin(), t.trace.begin() + static_cast<std::ptrdiff_t>(upto));
    done.color = kTraceColor;
    done.width = 2.0;
    done.label = m.skeleton.names[static_cast<std::size_t>(opt.trace_joint)];
    s.curves.push_back(std::move(all));
    s.curves.push_back(std::move(done));
  }
  if (with_title) s.title = t.label;
  if (!opt.follow) s.ground = opt.ground;
  return s;
}

}  // namespace

namespace {

// The root's place on the floor (x, 0, z) in a pose: what a following camera tracks.
Vec3 floor_point(const Vec3& root) { return Vec3(root.x(), 0, root.z()); }

// One panel per motion with a fixed framing from every frame's joints (and
// the trace) and one common scale, so the bodies compare at equal size; with
// opt.follow, from the joints relative to the root's floor point, so the
// camera can follow each body and the bodies fill their panels.
std::vector<Track> panel_tracks(const std::vector<const Motion*>& motions, const std::vector<std::string>& labels,
                                const VideoOptions& opt, int panel_w, int panel_h, bool titled) {
  static const Rgb kPanelColors[] = {{0.15, 0.15, 0.2}, {0.45, 0.15, 0.55}, {0.1, 0.45, 0.45}, {0.5, 0.35, 0.1}};
  const int n = static_cast<int>(motions.size());
  std::vector<Track> tracks(static_cast<std::size_t>(n));
  double mpp = 0;
  std::vector<Scene> extent(static_cast<std::size_t>(n));
  Camera cam = opt.camera;
  cam.width = panel_w;
  cam.height = panel_h;
  for (int i = 0; i < n; ++i) {
    auto& t = tracks[static_cast<std::size_t>(i)];
    t.motion = motions[static_cast<std::size_t>(i)];
    t.label = static_cast<std::size_t>(i) < labels.size() ? labels[static_cast<std::size_t>(i)] : "";
    t.color = kPanelColors[i % 4];
    const Motion& m = *t.motion;
    const auto nj = static_cast<std::size_t>(m.joint_count());
    Scene& s = extent[static_cast<std::size_t>(i)];
    Curve everything;
    std::vector<Transform> model(nj);
    for (int f = 0; f < m.frame_count(); ++f) {
      forward_kinematics(m.skeleton, m.frame(f), model);
      const Vec3 shift = opt.follow ? floor_point(model[0].translation) : Vec3::Zero();
      for (std::size_t j = 0; j < nj; ++j) {
        everything.points.push_back(model[j].translation - shift);
        if (j < m.skeleton.has_end_site.size() && m.skeleton.has_end_site[j])
          everything.points.push_back(end_site_position(m.skeleton, model, static_cast<int>(j)) - shift);
      }
      if (opt.trace_joint >= 0) t.trace.push_back(model[static_cast<std::size_t>(opt.trace_joint)].translation);
    }
    s.curves.push_back(std::move(everything));
    if (!opt.follow) s.ground = opt.ground;
    if (titled) s.title = t.label.empty() ? " " : t.label;
    if (opt.camera.metres_per_pixel <= 0) mpp = std::max(mpp, frame_scene(s, cam).metres_per_pixel);
  }
  if (opt.camera.metres_per_pixel > 0) mpp = opt.camera.metres_per_pixel;
  cam.metres_per_pixel = mpp;
  // Shared vertical centre, so the floors line up across panels.
  double vlo = 1e300, vhi = -1e300;
  for (const auto& s : extent) {
    Eigen::Vector2d lo, hi;
    if (detail::plane_bounds(s, cam.view, lo, hi)) vlo = std::min(vlo, lo.y()), vhi = std::max(vhi, hi.y());
  }
  for (int i = 0; i < n; ++i) {
    auto& fr = tracks[static_cast<std::size_t>(i)].framing;
    fr = frame_scene(extent[static_cast<std::size_t>(i)], cam);
    if (vlo <= vhi && !cam.fixed_bounds) fr.centre_plane.y() = (vlo + vhi) / 2;
  }
  return tracks;
}

}  // namespace

void render_video_side_by_side(const std::vector<const Motion*>& motions, const std::vector<std::string>& labels,
                               const VideoOptions& opt, const std::string& path) {
  const int W = opt.camera.width, H = opt.camera.height;
  if (motions.empty()) throw Error("video '" + path + "': no motions to draw");
  if (W <= 0 || H <= 0 || W % 2 || H % 2)
    throw Error("video '" + path + "': size " + std::to_string(W) + "x" + std::to_string(H) +
                " must be positive and even (H.264 with yuv420p needs even sizes)");
  if (!(opt.fps > 0 && opt.fps <= 240)) throw Error("video '" + path + "': fps must be in (0, 240]");
  for (const Motion* m : motions) {
    if (!m || m->frame_count() == 0) throw Error("video '" + path + "': a motion has no frames");
    if (opt.trace_joint >= m->joint_count())
      throw Error("video '" + path + "': trace joint " + std::to_string(opt.trace_joint) + " is outside 0.." +
                  std::to_string(m->joint_count() - 1));
  }
  const std::string ffmpeg = find_ffmpeg();  // fail before drawing anything
  (void)ffmpeg;

  const int n = static_cast<int>(motions.size());
  const int top = opt.title.empty() ? 0 : 30;  // frame-wide title strip
  const int panel_w = W / n;
  const bool titled = n > 1 || !labels.empty();
  const int counter_strip = 22;  // the time / frame counter's own strip: never over a foot
  const std::vector<Track> tracks = panel_tracks(motions, labels, opt, panel_w, H - top - counter_strip, titled);

  double duration = 0;
  for (const Motion* m : motions) duration = std::max(duration, m->duration());
  // Bounded in double before it becomes an int (a 1e8-frame clip at 240 fps would overflow it).
  const double frame_count = std::floor(duration * opt.fps + 1e-9) + 1;
  if (!(frame_count <= kMaxVideoFrames))
    throw Error("video '" + path + "': " + std::to_string(duration) + " s at " + std::to_string(opt.fps) +
                " fps is more frames than legwork renders (" + std::to_string(static_cast<int>(kMaxVideoFrames)) +
                "); use --frames to pick a part");
  const int frames = static_cast<int>(frame_count);

  detail::Canvas canvas(W, H);
  FfmpegPipe pipe(path, W, H, opt.fps);
  std::vector<Pose> poses;
  for (const Motion* m : motions) poses.emplace_back(m->skeleton);
  cairo_t* cr = canvas.cr();
  const auto progress = io::progress_printer("video " + path + ": frame");
  for (int k = 0; k < frames; ++k) {
    const double time = k / opt.fps;
    canvas.clear();
    if (detail::layout_recording()) detail::layout_begin(cr, path + " frame " + std::to_string(k), W, H);
    for (int i = 0; i < n; ++i) {
      const auto& t = tracks[static_cast<std::size_t>(i)];
      const Scene s = frame_scene_of(t, time, opt, poses[static_cast<std::size_t>(i)], titled);
      Framing fr = t.framing;
      if (opt.follow) fr.centre_plane += project(fr.view, floor_point(poses[static_cast<std::size_t>(i)].translations[0]));
      cairo_save(cr);
      cairo_translate(cr, i * panel_w, top);
      detail::draw_scene(cr, s, fr);
      cairo_restore(cr);
      if (i > 0) {
        cairo_set_source_rgb(cr, 0.8, 0.8, 0.82);
        cairo_set_line_width(cr, 1);
        cairo_move_to(cr, i * panel_w + 0.5, top + 6);
        cairo_line_to(cr, i * panel_w + 0.5, H - 6);
        cairo_stroke(cr);
      }
    }
    if (!opt.title.empty()) detail::title(cr, 10, 21, opt.title, 15, W - 20);
    const Motion& m0 = *motions[0];
    const int src = std::min(m0.frame_count() - 1, static_cast<int>(std::lround(time * m0.fps)));
    char counter[96];
    std::snprintf(counter, sizeof counter, "t = %.2f s   frame %d / %d", time, src, m0.frame_count() - 1);
    detail::text(cr, W - 10, H - 10, counter, 12, Align::Right, {0.25, 0.25, 0.3});
    pipe.write_frame(canvas.surface());
    progress(k + 1, frames, "");
  }
  pipe.close();
}

void render_video(const Motion& m, const VideoOptions& opt, const std::string& path) {
  render_video_side_by_side({&m}, {}, opt, path);
}

void write_video_still(const std::string& video, const std::string& png, double seconds) {
  const std::string ffmpeg = find_ffmpeg();
  // -ss after -i decodes up to the time, so a time past a short video's end
  // gives no frame: try the asked time, then the first frame.
  for (double t : {seconds, 0.0}) {
    std::error_code ec;
    std::filesystem::remove(png, ec);
    const std::string cmd = shell_quote(ffmpeg) + " -y -loglevel error -i " + shell_quote(video) + " -ss " +
                            detail::format_number(t, 3) + " -frames:v 1 -update 1 " + shell_quote(png) + " </dev/null";
    if (std::system(cmd.c_str()) == 0 && std::filesystem::exists(png, ec) && std::filesystem::file_size(png, ec) > 0) return;
  }
  throw Error("ffmpeg could not take a still of '" + video + "' for '" + png + "'");
}

}  // namespace legwork::render
