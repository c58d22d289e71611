// Composed pictures and videos (see compose.hpp).
#include <legwork/render/compose.hpp>

#include <legwork/core/contacts.hpp>
#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/io/progress.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace legwork::render {

namespace fs = std::filesystem;

std::vector<Footprint> detect_footprints(const Motion& m, int first, int last) {
  std::vector<Footprint> out;
  const auto& roles = m.skeleton.roles;
  if (!roles.has(Role::LeftAnkle) || !roles.has(Role::RightAnkle) || last < first) return out;
  const auto contacts = foot_contacts(trim(m, first, last));  // the one detector (core/contacts.hpp)
  const auto pos = joint_positions(m);
  const auto nj = static_cast<std::size_t>(m.joint_count());
  auto at = [&](int f, int j) { return pos[static_cast<std::size_t>(f) * nj + static_cast<std::size_t>(j)]; };
  const int min_run = std::max(2, static_cast<int>(0.1 * m.fps));
  for (int foot = 0; foot < 2; ++foot) {
    const int ankle = roles[foot == 0 ? Role::LeftAnkle : Role::RightAnkle];
    const int toe = roles[foot == 0 ? Role::LeftToe : Role::RightToe];
    const auto& down = contacts[static_cast<std::size_t>(foot)];
    for (int f = first; f <= last;) {
      if (!down[static_cast<std::size_t>(f - first)]) { ++f; continue; }
      int e = f;
      Vec3 a = Vec3::Zero(), dir = Vec3::Zero();
      for (; e <= last && down[static_cast<std::size_t>(e - first)]; ++e) {
        a += at(e, ankle);
        if (toe >= 0) dir += at(e, toe) - at(e, ankle);
      }
      if (e - f >= min_run) {
        a /= e - f;
        const double heading = toe >= 0 ? std::atan2(dir.x(), dir.z()) : 0.0;
        // The sole's origin sits ~3 cm ahead of the ankle, on the floor.
        out.push_back({Vec3(a.x() + 0.03 * std::sin(heading), 0.0, a.z() + 0.03 * std::cos(heading)), heading, foot == 0});
      }
      f = e;
    }
  }
  return out;
}

std::vector<int> sample_frames(int first, int last, int every) {
  std::vector<int> out;
  if (every <= 0) {
    const int n = std::min(6, last - first + 1);
    for (int i = 0; i < n; ++i) out.push_back(first + (n > 1 ? i * (last - first) / (n - 1) : 0));
    return out;
  }
  for (int f = first; f <= last; f += every) out.push_back(f);
  if (out.back() != last && last - out.back() >= every / 2) out.push_back(last);
  return out;
}

int fitted_height(const Motion& m, int first, int last, View view, int width) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  const auto pos = joint_positions(m);
  const auto nj = static_cast<std::size_t>(m.joint_count());
  for (int f = first; f <= last; ++f)
    for (std::size_t j = 0; j < nj; ++j) {
      Vec3 p = pos[static_cast<std::size_t>(f) * nj + j];
      for (int floor = 0; floor < (view == View::Top ? 1 : 2); ++floor) {
        if (floor) p.y() = 0;
        const auto q = project(view, p);
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
      }
    }
  const double aspect = (hi.y() - lo.y()) / std::max(hi.x() - lo.x(), 1e-3);
  return std::clamp(static_cast<int>(width * 0.84 * aspect) + 110, 240, 960) / 2 * 2;
}

void render_arc(const Skeleton& skel, const std::vector<Pose>& ghosts, const Curve& arc, const std::string& title,
                const std::string& base) {
  std::vector<Panel> panels;
  for (View v : {View::Side, View::Front}) {
    Panel p;
    p.camera.view = v;
    p.camera.width = 480;
    p.camera.height = 480;
    for (const auto& g : ghosts) p.scene.figures.push_back(make_figure(skel, g, 0.18));
    p.scene.curves.push_back(arc);
    p.scene.title = view_name(v) + " view";
    panels.push_back(std::move(p));
  }
  for (const char* ext : {".svg", ".png"}) render_panels(panels, 2, base + ext, title);
}

void render_slide_video(const Skeleton& skel, const SlideVideo& v, const std::string& path) {
  const fs::path dir = fs::temp_directory_path() / ("legwork_slide_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto& times = v.key_times;
  const int last_key = static_cast<int>(times.size()) - 1;
  auto placed = [&](const Pose& p, double slot) {
    Pose q = p;
    q.translations[0].z() = slot * v.spacing;
    q.translations[0].x() = 0;
    return q;
  };
  Scene base;
  for (std::size_t k = 0; k < v.key_poses.size(); ++k)
    base.figures.push_back(make_figure(skel, placed(v.key_poses[k], static_cast<double>(k)), 0.22, v.labels[k]));
  Camera cam;
  cam.view = View::Side;
  cam.width = 960;
  cam.height = 360;
  cam.fixed_bounds = true;
  cam.bounds_min = Vec3(-0.5, 0, -0.7);
  cam.bounds_max = Vec3(0.5, 2.0, last_key * v.spacing + 0.7);
  const int frames = static_cast<int>(std::lround(v.duration * 4));  // quarter-frame steps, slowed down
  Pose pose(skel);
  const auto progress = io::progress_printer("sliding video: frame");
  for (int f = 0; f <= frames; ++f) {
    const double t = v.duration * f / frames;
    int k = 0;
    while (k < last_key - 1 && t >= times[static_cast<std::size_t>(k + 1)]) ++k;
    const double slot = k + (t - times[static_cast<std::size_t>(k)]) /
                                (times[static_cast<std::size_t>(k + 1)] - times[static_cast<std::size_t>(k)]);
    v.sample(t, pose.ref());
    Scene s = base;
    s.figures.push_back(make_figure(skel, placed(pose, slot), 1.0));
    char title[64];
    std::snprintf(title, sizeof title, "sliding through the key poses - frame %.2f", t);
    s.title = title;
    char name[32];
    std::snprintf(name, sizeof name, "f%05d.png", f);
    progress(f + 1, frames + 1, "");
    render_scene(s, cam, (dir / name).string());
  }
  const std::string cmd = "ffmpeg -loglevel error -y -framerate 24 -i '" + (dir / "f%05d.png").string() +
                          "' -c:v libx264 -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' '" + path + "'";
  const int rc = std::system(cmd.c_str());
  fs::remove_all(dir);
  if (rc != 0) throw Error("ffmpeg failed writing '" + path + "' (is ffmpeg installed?)");
}

void render_walk_top(const Motion& walk, const std::vector<Vec3>* path, const std::vector<Footprint>& footprints,
                     const std::string& title, const std::string& out) {
  Scene s;
  if (path) {
    Curve c;
    c.points = *path;
    c.color = {0.6, 0.6, 0.6};
    c.width = 3;
    c.label = "path";
    s.curves.push_back(c);
  }
  Curve root;
  for (int f = 0; f < walk.frame_count(); ++f) {
    Vec3 p = walk.frame(f).translations[0];
    root.points.push_back(Vec3(p.x(), 0, p.z()));
  }
  root.color = kTraceColor;
  root.label = "root";
  s.curves.push_back(root);
  s.footprints = footprints;
  // A few translucent figures along the walk.
  const int every = std::max(1, walk.frame_count() / 8);
  for (int f = 0; f < walk.frame_count(); f += every)
    s.figures.push_back(make_figure(walk.skeleton, walk.frame(f), 0.45));
  s.title = title;
  Camera cam;
  cam.view = View::Top;
  cam.width = 800;
  cam.height = 800;
  render_scene(s, cam, out);
}

}  // namespace legwork::render
