// legwork walkcycle: key poses -> mirrored full cycle -> no-slip walk along a
// path, with the animator's display aids (key-pose sheet, arcs, videos, top
// view) and a JSON report; `legwork walkcycle extract` turns a mocap walk into
// a key-pose file.
#include "command.hpp"

#include <legwork/core/fk.hpp>
#include <legwork/core/interpolate.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/gltf.hpp>
#include <legwork/io/text.hpp>
#include <legwork/render/render.hpp>
#include <legwork/walkcycle/offline/keys.hpp>
#include <legwork/walkcycle/offline/extract.hpp>
#include <legwork/walkcycle/offline/measure.hpp>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

namespace legwork::cli {
namespace {

namespace fs = std::filesystem;
namespace wc = legwork::walkcycle;
using nlohmann::json;

struct WalkArgs {
  std::string keys;  // walk.json, or frame list with --from-bvh
  std::string from_bvh;
  std::string skeleton;
  int frames = 0;
  double fps = 0;
  std::string shift;
  std::string path;
  std::string svg_path;
  double straight = 0;
  int steps = -1;
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

double r6(double v) { return std::round(v * 1e6) / 1e6 + 0.0; }

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string stem_of(const std::string& path) {
  fs::path p(path);
  return (p.parent_path() / p.stem()).string();
}

void ensure_parent(const std::string& path) {
  const auto parent = fs::path(path).parent_path();
  if (!parent.empty()) fs::create_directories(parent);
}

void write_motion(const std::string& path, const Motion& m, const std::string& what) {
  const auto ext = io::extension_of(path);
  ensure_parent(path);
  if (ext == ".bvh") io::write_bvh(path, m);
  else if (ext == ".glb") io::write_glb(path, m, {what, true});
  else throw Error("output '" + path + "' must end in .bvh or .glb");
  announce(what, path);
}

// Key-pose sheet: the five poses of the step, front and side, inactive ones x-ray.
void write_sheet(const wc::CycleModel& m, const WalkArgs& a, const std::string& name) {
  render::SheetOptions o;
  o.views.clear();
  for (const auto& v : split(a.sheet_views, ',')) o.views.push_back(render::parse_view(v));
  if (o.views.empty()) throw Error("--sheet-views: give at least one view");
  o.spacing = a.spacing;
  o.face_forward = false;
  std::vector<Pose> poses(m.step_keys.begin(), m.step_keys.end());
  const double half = m.half_cycle();
  const char* names[] = {"contact", "down", "pass", "up", "contact (mirror)"};
  for (int i = 0; i < 5; ++i) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s  f%g", names[i], i < 4 ? m.key_frames[static_cast<std::size_t>(i)] : half);
    o.labels.push_back(buf);
    if (!a.active.empty() && (a.active == names[i] || (i == 4 && a.active == "next"))) o.active = i;
  }
  if (!a.active.empty() && o.active < 0)
    throw Error("--active '" + a.active + "': expected contact, down, pass, up or next");
  o.title = "walk '" + name + "': key poses of one step (" + std::to_string(m.frames_per_cycle) + " frames per cycle)";
  ensure_parent(a.sheet);
  render::render_contact_sheet(m.skeleton, poses, o, a.sheet);
  announce("key-pose sheet", a.sheet);
}

json arc_outputs(const wc::CycleModel& m, const std::string& joint_name, const std::string& prefix) {
  const int j = wc::find_joint_or_role(m.skeleton, joint_name);
  if (j < 0) throw Error("--arc: unknown joint '" + joint_name + "'");
  const auto arc = wc::trace_arc(m, j, 1);
  const auto fine = wc::trace_arc(m, j, 4);
  const auto sm = wc::arc_smoothness(fine);
  const std::string base = prefix + "_arc_" + m.skeleton.names[static_cast<std::size_t>(j)];
  ensure_parent(base);
  // CSV: one row per frame.
  std::string csv = "frame,x,y,z,key\n";
  const char* key_names[] = {"contact", "down", "pass", "up", "contact2", "down2", "pass2", "up2"};
  for (std::size_t i = 0; i < arc.points.size(); ++i) {
    std::string key;
    for (std::size_t k = 0; k < arc.key_indices.size(); ++k)
      if (arc.key_indices[k] == static_cast<int>(i)) key = key_names[k];
    char buf[160];
    std::snprintf(buf, sizeof buf, "%zu,%.6f,%.6f,%.6f,%s\n", i, arc.points[i].x(), arc.points[i].y(), arc.points[i].z(), key.c_str());
    csv += buf;
  }
  io::write_text_file(base + ".csv", csv);
  // Pictures: side and front views of the closed arc over translucent key poses.
  std::vector<render::Panel> panels;
  for (render::View v : {render::View::Side, render::View::Front}) {
    render::Panel p;
    p.camera.view = v;
    p.camera.width = 480;
    p.camera.height = 480;
    for (int k = 0; k < 4; ++k)
      p.scene.figures.push_back(render::make_figure(m.skeleton, m.step_keys[static_cast<std::size_t>(k)], 0.18));
    render::Curve c;
    c.points = fine.points;
    c.points.push_back(fine.points.front());
    c.width = 2.0;
    for (std::size_t k = 0; k < fine.key_indices.size(); ++k) {
      c.marks.push_back(fine.key_indices[k]);
      c.mark_labels.push_back(std::string(1, "CDPU"[k % 4]) + (k >= 4 ? "'" : ""));
    }
    c.label = m.skeleton.names[static_cast<std::size_t>(j)];
    p.scene.curves.push_back(c);
    p.scene.title = render::view_name(v) + " view";
    panels.push_back(std::move(p));
  }
  char title[200];
  std::snprintf(title, sizeof title, "%s arc over the cycle - jerk ratio %.2f (frame %.1f), curvature jump %.0f deg",
                m.skeleton.names[static_cast<std::size_t>(j)].c_str(), sm.jerk_ratio, sm.jerk_frame, sm.max_curvature_jump_deg);
  for (const char* ext : {".svg", ".png"}) render::render_panels(panels, 2, base + ext, title);
  announce("arc", base + ".svg");
  const bool jerky = sm.jerk_ratio > 5.0 && sm.extent_m > 0.1;  // (a hand held still has a tiny, noisy arc)
  std::printf("arc %s: spans %.2f m, jerk ratio %.2f at frame %.1f, largest curvature jump %.1f deg at frame %.1f%s\n",
              m.skeleton.names[static_cast<std::size_t>(j)].c_str(), sm.extent_m, sm.jerk_ratio, sm.jerk_frame,
              sm.max_curvature_jump_deg, sm.jump_frame, jerky ? "  <- jerky: check the keys near this frame" : "");
  return {{"joint", m.skeleton.names[static_cast<std::size_t>(j)]},
          {"extent_m", r6(sm.extent_m)},
          {"jerky", jerky},
          {"jerk_ratio", r6(sm.jerk_ratio)},
          {"jerk_frame", r6(sm.jerk_frame)},
          {"max_curvature_jump_deg", r6(sm.max_curvature_jump_deg)},
          {"jump_frame", r6(sm.jump_frame)},
          {"csv", base + ".csv"}};
}

// Sliding display: the animated model slides through the five translucent
// key poses spread out along +z (document 001, "sliding" + "x-ray").
void write_slide_video(const wc::CycleModel& m, double spacing, const std::string& path) {
  const fs::path dir = fs::temp_directory_path() / ("legwork_slide_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const double half = m.half_cycle();
  std::array<double, 5> times{m.key_frames[0], m.key_frames[1], m.key_frames[2], m.key_frames[3], half};
  auto placed = [&](const Pose& p, double slot) {
    Pose q = p;
    q.translations[0].z() = slot * spacing;
    q.translations[0].x() = 0;
    return q;
  };
  render::Scene base;
  for (int k = 0; k < 5; ++k)
    base.figures.push_back(render::make_figure(m.skeleton, placed(m.step_keys[static_cast<std::size_t>(k)], k), 0.22,
                                               std::array<const char*, 5>{"contact", "down", "pass", "up", "contact'"}[static_cast<std::size_t>(k)]));
  render::Camera cam;
  cam.view = render::View::Side;
  cam.width = 960;
  cam.height = 360;
  cam.fixed_bounds = true;
  cam.bounds_min = Vec3(-0.5, 0, -0.7);
  cam.bounds_max = Vec3(0.5, 2.0, 4 * spacing + 0.7);
  const int frames = static_cast<int>(std::lround(half * 4));  // the step at quarter-frame steps, slowed down
  Pose pose(m.skeleton);
  for (int f = 0; f <= frames; ++f) {
    const double t = half * f / frames;
    int k = 0;
    while (k < 3 && t >= times[static_cast<std::size_t>(k + 1)]) ++k;
    const double slot = k + (t - times[static_cast<std::size_t>(k)]) / (times[static_cast<std::size_t>(k + 1)] - times[static_cast<std::size_t>(k)]);
    wc::sample_cycle(m, t, pose.ref());
    render::Scene s = base;
    s.figures.push_back(render::make_figure(m.skeleton, placed(pose, slot), 1.0));
    s.figures.back().color = {0.1, 0.35, 0.8};
    char title[64];
    std::snprintf(title, sizeof title, "sliding through the key poses - frame %.2f", t);
    s.title = title;
    char name[32];
    std::snprintf(name, sizeof name, "f%05d.png", f);
    std::fprintf(stderr, "\rsliding video: frame %d/%d", f + 1, frames + 1);
    if (f == frames) std::fprintf(stderr, "\n");
    render::render_scene(s, cam, (dir / name).string());
  }
  ensure_parent(path);
  const std::string cmd = "ffmpeg -loglevel error -y -framerate 24 -i '" + (dir / "f%05d.png").string() +
                          "' -c:v libx264 -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' '" + path + "'";
  const int rc = std::system(cmd.c_str());
  fs::remove_all(dir);
  if (rc != 0) throw Error("ffmpeg failed writing '" + path + "' (is ffmpeg installed?)");
  announce("sliding video", path);
}

void write_top(const wc::WalkResult& w, const wc::Path* path, const std::string& out, const std::string& name) {
  render::Scene s;
  if (path) {
    render::Curve c;
    c.points = path->points;
    c.color = {0.6, 0.6, 0.6};
    c.width = 3;
    c.label = "path";
    s.curves.push_back(c);
  }
  render::Curve root;
  for (int f = 0; f < w.motion.frame_count(); ++f) {
    Vec3 p = w.motion.frame(f).translations[0];
    root.points.push_back(Vec3(p.x(), 0, p.z()));
  }
  root.color = {0.1, 0.35, 0.8};
  root.label = "root";
  s.curves.push_back(root);
  for (const auto& st : w.footsteps) s.footprints.push_back({0.5 * (st.heel + st.ball), st.heading, st.left});
  // A few translucent figures along the walk.
  const int every = std::max(1, w.motion.frame_count() / 8);
  for (int f = 0; f < w.motion.frame_count(); f += every)
    s.figures.push_back(render::make_figure(w.motion.skeleton, w.motion.frame(f), 0.25));
  char title[160];
  std::snprintf(title, sizeof title, "walk '%s' from above: %d steps, %zu footprints, turning %.0f deg", name.c_str(), w.steps,
                w.footsteps.size(), rad2deg(w.turning));
  s.title = title;
  render::Camera cam;
  cam.view = render::View::Top;
  cam.width = 800;
  cam.height = 800;
  ensure_parent(out);
  render::render_scene(s, cam, out);
  announce("top view", out);
}

wc::WalkKeys load_keys(const WalkArgs& a, Skeleton& skel) {
  if (!a.from_bvh.empty()) {
    io::BvhReadOptions o;
    o.drop_first_frame = false;
    auto clip = io::read_bvh(a.from_bvh, o);
    std::vector<int> frames;
    for (const auto& s : split(a.keys, ',')) {
      char* end = nullptr;
      const long v = std::strtol(s.c_str(), &end, 10);
      if (end != s.c_str() + s.size()) throw Error("--keys '" + a.keys + "': with --from-bvh, give four frame numbers like 0,3,6,9");
      frames.push_back(static_cast<int>(v));
    }
    skel = clip.motion.skeleton;
    return wc::keys_from_frames(clip.motion, frames, a.frames > 0 ? a.frames : 24, 24.0);
  }
  wc::WalkFile w = wc::load_walk(a.keys, a.skeleton);
  skel = std::move(w.skeleton);
  return std::move(w.keys);
}

// The walk's keys: read (or taken from a clip), retimed and shifted as asked.
wc::WalkKeys prepared_keys(const WalkArgs& a, Skeleton& skel) {
  wc::WalkKeys keys = load_keys(a, skel);
  if (a.frames > 0) {
    if (a.frames % 2 || a.frames < 8) throw Error("--frames: expected an even number of frames per cycle, at least 8");
    keys = wc::retime(keys, a.frames);
  }
  if (!a.shift.empty()) {
    auto extra = wc::parse_shift_spec(a.shift, skel);
    for (auto [j, d] : extra) {
      bool replaced = false;
      for (auto& [k, e] : keys.shift)
        if (k == j) e = d, replaced = true;
      if (!replaced) keys.shift.emplace_back(j, d);
    }
  }
  return keys;
}

// The cycle's figures: printed, and the report's cycle fields.
json cycle_report(const wc::CycleModel& model, const std::string& name) {
  const auto seam = wc::measure_loop_seam(model);
  const auto feet = wc::key_foot_heights(model);
  std::printf("cycle: %d frames, step length %.3f m, loop seam %.2e m / %.2e m/s\n", model.frames_per_cycle,
              wc::step_length(model), seam.position_m, seam.velocity_mps);

  json report;
  report["walk"] = name;
  report["frames_per_cycle"] = model.frames_per_cycle;
  report["fps"] = model.fps;
  report["step_length_m"] = r6(wc::step_length(model));
  report["loop_seam_error"] = seam.position_m;  // metres (position; velocity below)
  report["loop_seam_error_m"] = seam.position_m;
  report["loop_seam_velocity_error_mps"] = seam.velocity_mps;
  report["key_frames"] = {model.key_frames[0], model.key_frames[1], model.key_frames[2], model.key_frames[3]};
  report["key_foot_height_mm"] = json::array();
  for (double h : feet) report["key_foot_height_mm"].push_back(r6(h * 1e3));
  const auto floor = wc::cycle_floor_contact(model);
  report["cycle_lowest_foot_mm"] = r6(floor.lowest_m * 1e3);
  report["cycle_lowest_foot_frame"] = floor.at_frame;
  report["floor_clamp"] = model.floor_clamp;
  report["floor_lift_mm_max"] = r6(floor.max_lift_m * 1e3);
  report["floor_lift_frame"] = floor.lift_frame;
  if (floor.max_lift_m > 0.01)
    std::printf("note: between the keys a foot would dip %.0f mm below the floor at frame %.2f%s\n", floor.max_lift_m * 1e3,
                floor.lift_frame, model.floor_clamp ? "; the root is lifted there (floor_clamp)" : " (floor_clamp is off)");

  return report;
}

// The walk (along a path, straight, a number of steps) or the in-place
// cycle; its figures printed and added to the report.
Motion walk_or_cycle(const wc::CycleModel& model, const WalkArgs& a, const std::string& name, json& report, bool& walked) {
  std::unique_ptr<wc::Path> path;
  wc::WalkOptions wo;
  wo.fps = a.fps;
  if (!a.path.empty()) path = std::make_unique<wc::Path>(wc::read_path(a.path));
  else if (!a.svg_path.empty()) path = std::make_unique<wc::Path>(wc::parse_svg_path(a.svg_path, "--svg-path"));
  else if (a.straight > 0) path = std::make_unique<wc::Path>(wc::straight_path(a.straight));
  else if (a.steps >= 0) {
    path = std::make_unique<wc::Path>(wc::straight_path(1e6));
    wo.steps = a.steps;
  }
  Motion result;
  if (path) {
    const auto t0 = std::chrono::steady_clock::now();
    const wc::WalkResult w = wc::walk_path(model, *path, wo);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const auto slip = wc::measure_stance_slip(model, w.motion, w.labels);
    std::printf("walk: %d steps, %d frames at %g fps (%.1f ms), path %.2f m, turning %.1f deg, end %.3f m from the path's end, "
                "max deviation %.3f m\n",
                w.steps, w.motion.frame_count(), w.motion.fps, ms, w.path_length, rad2deg(w.turning), w.end_distance,
                w.max_path_deviation);
    std::printf("stance slip: max %.2e mm, mean %.2e mm over %d pivot phases\n", slip.max_mm, slip.mean_mm, slip.phases);
    report["steps"] = w.steps;
    report["frames"] = w.motion.frame_count();
    report["output_fps"] = w.motion.fps;
    report["stance_slip_mm_max"] = slip.max_mm;
    report["stance_slip_mm_mean"] = slip.mean_mm;
    report["stance_phases"] = slip.phases;
    report["path_length_m"] = r6(w.path_length);
    report["turning_deg"] = r6(rad2deg(w.turning));
    report["turning_abs_deg"] = r6(rad2deg(w.turning_abs));
    report["end_distance_m"] = r6(w.end_distance);
    report["max_path_deviation_m"] = r6(w.max_path_deviation);
    json steps = json::array();
    for (const auto& s : w.footsteps)
      steps.push_back({{"step", s.step}, {"frame", s.frame}, {"foot", s.left ? "left" : "right"},
                       {"heel", {r6(s.heel.x()), r6(s.heel.z())}}, {"heading_deg", r6(rad2deg(s.heading))}});
    report["footsteps"] = steps;
    if (!a.top.empty()) write_top(w, path.get(), a.top, name);
    result = w.motion;
  } else {
    result = wc::bake_cycle(model);
    report["steps"] = 2;
    report["frames"] = result.frame_count();
    report["stance_slip_mm_max"] = nullptr;  // in place: the feet slide by design
    if (!a.top.empty()) throw Error("--top needs a walk: give --path, --straight or --steps");
  }
  walked = path != nullptr;
  return result;
}

void write_walk_video(const Motion& result, const Skeleton& skel, const WalkArgs& a, const std::string& name) {
  if (a.video.empty()) return;
  render::VideoOptions vo;
  vo.camera.view = render::parse_view(a.video_view);
  vo.camera.width = 960;
  vo.camera.height = 540;
  vo.fps = 30;
  vo.trace_joint = skel.roles[Role::LeftToe] >= 0 ? skel.roles[Role::LeftToe] : skel.roles[Role::LeftAnkle];
  vo.title = "walk '" + name + "'";
  ensure_parent(a.video);
  render::render_video(result, vo, a.video);
  announce("video", a.video);
}

void run_walk(const WalkArgs& a) {
  if (a.keys.empty()) throw Error("walkcycle: --keys walk.json is required (or --from-bvh clip.bvh --keys 0,3,6,9)");
  int sources = (!a.path.empty()) + (!a.svg_path.empty()) + (a.straight > 0) + (a.steps >= 0);
  if (sources > 1 && !(sources == 2 && a.steps >= 0 && a.straight > 0))
    throw Error("walkcycle: give one of --path, --svg-path, --straight, --steps");
  if (a.out.empty() && a.cycle_out.empty() && a.sheet.empty() && a.arc.empty() && a.report.empty() && a.video.empty() &&
      a.slide_video.empty() && a.top.empty())
    throw Error("walkcycle: nothing to write; give --out (and/or --cycle-out, --sheet, --arc, --video, --report)");
  Skeleton skel;
  const wc::WalkKeys keys = prepared_keys(a, skel);
  const std::string name = keys.name.empty() ? fs::path(a.keys).stem().string() : keys.name;
  std::fprintf(stderr, "walkcycle: building the cycle of '%s' (%d frames at %g fps)\n", name.c_str(), keys.frames_per_cycle, keys.fps);
  const wc::CycleModel model = wc::build_cycle(skel, keys);
  json report = cycle_report(model, name);

  if (!a.cycle_out.empty()) write_motion(a.cycle_out, wc::bake_cycle(model), "in-place cycle");
  if (!a.sheet.empty()) write_sheet(model, a, name);
  if (!a.arc.empty()) {
    const std::string prefix = !a.arc_out.empty() ? a.arc_out : stem_of(!a.out.empty() ? a.out : (!a.sheet.empty() ? a.sheet : a.report));
    report["arcs"] = json::array();
    for (const auto& j : split(a.arc, ',')) report["arcs"].push_back(arc_outputs(model, j, prefix));
  }
  if (!a.slide_video.empty()) write_slide_video(model, a.spacing, a.slide_video);

  bool walked = false;
  const Motion result = walk_or_cycle(model, a, name, report, walked);
  if (!a.out.empty()) write_motion(a.out, result, walked ? "walk" : "in-place cycle");
  write_walk_video(result, skel, a, name);
  if (!a.report.empty()) {
    ensure_parent(a.report);
    io::write_text_file(a.report, report.dump(2) + "\n");
    announce("report", a.report);
  }
}

struct ExtractArgs {
  std::string input;
  std::string out;
  int frames = 0;
  double fps = 24;
  std::string report;
  std::string sheet;
  std::string name;
};

void run_extract(const ExtractArgs& a) {
  io::BvhReadOptions o;
  o.drop_first_frame = true;
  std::fprintf(stderr, "walkcycle extract: reading %s\n", a.input.c_str());
  const auto clip = io::read_bvh(a.input, o);
  wc::ExtractOptions eo;
  eo.frames_per_cycle = a.frames;
  eo.fps = a.fps;
  const wc::Extraction ex = wc::extract_walk(clip.motion, eo);
  wc::WalkKeys keys = ex.keys;
  keys.name = a.name.empty() ? fs::path(a.input).stem().string() : a.name;
  keys.skeleton_path = fs::relative(fs::absolute(a.input), fs::absolute(fs::path(a.out).parent_path().empty() ? "." : fs::path(a.out).parent_path())).string();
  ensure_parent(a.out);
  wc::write_walk_keys(a.out, keys, clip.motion.skeleton);
  std::printf("%zu steps found (%d used), cycle %.3f s -> %d frames at %g fps; timing down %.2f pass %.2f up %.2f\n",
              ex.steps.size(), ex.steps_used, ex.cycle_seconds, keys.frames_per_cycle, keys.fps, keys.key_frames[1],
              keys.key_frames[2], keys.key_frames[3]);
  std::printf("resynthesis vs the clip's mean cycle: joint positions %.1f mm mean, %.1f mm max\n", ex.resynthesis_mean_mm,
              ex.resynthesis_max_mm);
  announce("key poses", a.out);
  if (!a.sheet.empty()) {
    WalkArgs wa;
    wa.sheet = a.sheet;
    write_sheet(wc::build_cycle(clip.motion.skeleton, keys), wa, keys.name);
  }
  if (!a.report.empty()) {
    json r;
    r["clip"] = a.input;
    r["frames"] = clip.motion.frame_count();
    r["fps"] = clip.motion.fps;
    r["cycle_seconds"] = r6(ex.cycle_seconds);
    r["steps_found"] = ex.steps.size();
    r["steps_used"] = ex.steps_used;
    r["resynthesis_mean_mm"] = r6(ex.resynthesis_mean_mm);
    r["resynthesis_max_mm"] = r6(ex.resynthesis_max_mm);
    json steps = json::array();
    for (const auto& s : ex.steps)
      steps.push_back({{"foot", s.left ? "left" : "right"}, {"contact", s.contact}, {"down", s.down}, {"pass", s.pass},
                       {"up", s.up}, {"next_contact", s.next_contact}, {"used", s.used}});
    r["steps"] = steps;
    ensure_parent(a.report);
    io::write_text_file(a.report, r.dump(2) + "\n");
    announce("report", a.report);
  }
}

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
  auto a = std::make_shared<WalkArgs>();
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
  cmd->add_option("--straight", a->straight, "walk this many metres straight ahead (+z)")->check(CLI::PositiveNumber);
  cmd->add_option("--steps", a->steps, "walk exactly this many steps straight ahead, then stop")->check(CLI::NonNegativeNumber);
  cmd->add_option("--out,-o", a->out, "the walk (or, with no path, the in-place cycle): .bvh or .glb");
  cmd->add_option("--cycle-out", a->cycle_out, "the in-place loop (frame N = frame 0 left out): .bvh or .glb");
  cmd->add_option("--sheet", a->sheet, "key-pose sheet: the five poses of a step side by side (.png or .svg)");
  cmd->add_option("--spacing", a->spacing, "metres between poses on the sheet / in the sliding video")->check(CLI::PositiveNumber);
  cmd->add_option("--sheet-views", a->sheet_views, "views of the sheet, comma-separated (front, side, three-quarter, top)");
  cmd->add_option("--active", a->active, "sheet: draw this pose opaque, the others x-ray (contact, down, pass, up, next)");
  cmd->add_option("--arc", a->arc, "trace these joints over the cycle: CSV + SVG/PNG with key frames marked, e.g. LeftHand,LeftToeBase");
  cmd->add_option("--arc-out", a->arc_out, "file prefix for the arcs (default: --out without extension)");
  cmd->add_option("--video", a->video, "MP4 of the walk (needs ffmpeg)");
  cmd->add_option("--video-view", a->video_view, "view of --video: side, front, three-quarter, top");
  cmd->add_option("--slide-video", a->slide_video, "MP4 of the model sliding through the translucent key poses");
  cmd->add_option("--top", a->top, "top view of the walk with the path and footprints (.png or .svg)");
  cmd->add_option("--report", a->report, "JSON report: stance_slip_mm_max, loop_seam_error, steps, frames, arcs...");

  auto* ext = cmd->add_subcommand("extract",
                                  "Detect contact, down, pass and up in a real walking clip (CMU BVH) and write a\n"
                                  "key-pose file to start a stylised walk from.\n"
                                  "Example: legwork walkcycle extract data/cmu/bvh/walking/07_01.bvh --out 07_01_keys.json --sheet keys.png");
  auto e = std::make_shared<ExtractArgs>();
  ext->add_option("input", e->input, "walking clip (BVH; frame 0, the CMU T-pose, is dropped)")->required()->check(CLI::ExistingFile);
  ext->add_option("--out,-o", e->out, "key-pose file to write (JSON)")->required();
  ext->add_option("--frames", e->frames, "frames per cycle (default: the clip's cycle at --fps, even)");
  ext->add_option("--fps", e->fps, "frame rate of the key-pose file (default 24)")->check(CLI::Range(1.0, 480.0));
  ext->add_option("--name", e->name, "walk name (default: the clip's file name)");
  ext->add_option("--sheet", e->sheet, "also draw the extracted key poses (.png or .svg)");
  ext->add_option("--report", e->report, "JSON report: detected steps, cycle length, resynthesis error");
  ext->callback([e] { run_extract(*e); });
  cmd->callback([a, ext] {
    if (ext->parsed()) return;
    run_walk(*a);
  });
}

LEGWORK_COMMAND(register_walkcycle, 40);

}  // namespace
}  // namespace legwork::cli
